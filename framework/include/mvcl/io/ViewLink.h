#pragma once
/// \file ViewLink.h
/// A two-way link between two views of one document: what one view's edits copy into the
/// other — its camera, its lens stack, its visible layers. Plain data, as session files and
/// undo steps hold it; the Document applies it (mvcl/controller/Document.h).

#include <mvcl/core/Export.h>

#include <cstdint>
#include <string>

namespace mvcl {

enum class LinkAspect : uint8_t { Camera, Lenses, Layers };

struct ViewLink {
    int a = 0; ///< view indices, a < b
    int b = 1;
    bool camera = false;
    bool lenses = false;
    bool layers = false;

    bool has(LinkAspect aspect) const {
        switch (aspect) {
        case LinkAspect::Camera: return camera;
        case LinkAspect::Lenses: return lenses;
        case LinkAspect::Layers: return layers;
        }
        return false;
    }
    void set(LinkAspect aspect, bool on) {
        switch (aspect) {
        case LinkAspect::Camera: camera = on; break;
        case LinkAspect::Lenses: lenses = on; break;
        case LinkAspect::Layers: layers = on; break;
        }
    }
    /// Links nothing: a link with no aspect left is removed.
    bool isEmpty() const { return !camera && !lenses && !layers; }
    /// Joins views x and y (either order).
    bool joins(int x, int y) const { return (a == x && b == y) || (a == y && b == x); }

    bool operator==(const ViewLink &other) const = default;
};

/// "camera", "lenses", "layers".
MVCL_EXPORT const char *linkAspectName(LinkAspect aspect);
/// The aspect named by linkAspectName; throws mvcl::Error(`source`, problem) for another word.
MVCL_EXPORT LinkAspect parseLinkAspect(const std::string &name, const std::string &source);

} // namespace mvcl
