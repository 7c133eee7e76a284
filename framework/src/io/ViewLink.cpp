#include <mvcl/io/ViewLink.h>

#include <mvcl/core/Error.h>

namespace mvcl {

const char *linkAspectName(LinkAspect aspect) {
    switch (aspect) {
    case LinkAspect::Camera: return "camera";
    case LinkAspect::Lenses: return "lenses";
    case LinkAspect::Layers: return "layers";
    }
    return "camera";
}

LinkAspect parseLinkAspect(const std::string &name, const std::string &source) {
    for (LinkAspect aspect : {LinkAspect::Camera, LinkAspect::Lenses, LinkAspect::Layers})
        if (name == linkAspectName(aspect)) return aspect;
    throw Error(source, "unknown link '" + name + "' (known: camera, lenses, layers)");
}

} // namespace mvcl
