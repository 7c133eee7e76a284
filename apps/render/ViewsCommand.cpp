#include "ViewsCommand.h"

#include <mvcl/controller/ViewSetup.h>
#include <mvcl/core/Error.h>
#include <mvcl/io/LoadedScene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/ImageIO.h>
#include <mvcl/view/LensOutlines.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

namespace mvcl::cli {

int sessionViewOf(const RenderCommandLine &cl) {
    if (cl.view.empty() || cl.view == "all") return 0;
    std::size_t used = 0;
    int index = -1;
    try {
        index = std::stoi(cl.view, &used);
    } catch (const std::exception &) {
    }
    if (used != cl.view.size() || index < 0)
        throw Error("command line", "--view: expected a view number (0, 1, ...) or 'all', got '" + cl.view + "'");
    return index;
}

void setViewStacks(RenderSession &session, const LensStack &lenses, const std::optional<CompareDescription> &compare) {
    if (compare) session.setLensStacks(lenses, compare->lenses, compare->divider);
    else session.setLensStack(lenses);
}

void drawViewOutlines(const LensStack &lenses, const std::optional<CompareDescription> &compare, Framebuffer &image) {
    if (compare) drawLensOutlines(lenses, compare->lenses, compare->divider, image);
    else drawLensOutlines(lenses, image);
}

int renderAllViews(const RenderCommandLine &cl, const LensRegistry &registry, const ViewRequest &request) {
    const ViewSetup setup = ViewSetup::prepare(request, registry);
    const SessionDescription &session = *setup.sessionFile;
    const LoadedScene loaded = LoadedScene::load(setup.sources(), setup.loadOptions); // one BVH for every view
    setup.renameLayers(*loaded.scene);
    const Scene &scene = *loaded.scene;
    const Tracer &tracer = *loaded.tracer;
    const RenderSettings settings = renderSettings(cl);
    const int count = int(session.views.size());
    Framebuffer all(cl.width * count, cl.height);
    for (int i = 0; i < count; ++i) {
        ViewSetup viewSetup = setup;
        viewSetup.session = session.view(i);
        if (i == 0) viewSetup.session.lenses = setup.session.lenses; // with the command line's --lens
        ViewRequest viewRequest = i == 0 ? request : ViewRequest{};
        viewRequest.origin = request.origin;
        const Camera camera = viewSetup.camera(scene, viewRequest, float(cl.width) / float(cl.height));
        RenderSession render(tracer);
        render.setSettings(settings);
        render.setCamera(camera);
        RayPolicy base;
        base.query(RayType::Primary).layerMask = viewSetup.session.visibleLayers;
        render.setBasePolicy(base);
        const std::optional<CompareDescription> &compare = session.views[std::size_t(i)].compare;
        setViewStacks(render, viewSetup.session.lenses, compare);
        render.renderUntilIdle();
        Framebuffer image = render.image();
        drawViewOutlines(viewSetup.session.lenses, compare, image);
        for (int y = 0; y < cl.height; ++y)
            for (int x = 0; x < cl.width; ++x) all.at(i * cl.width + x, y) = image.at(x, y);
    }
    const std::string output = cl.output.empty()
                                   ? "out/" + std::filesystem::path(request.sessionFile).stem().string() + "-views.png"
                                   : cl.output;
    try {
        writeImage(output, all);
    } catch (const Error &e) {
        std::fprintf(stderr, "mvcl-render: %s\n", e.what());
        return kExitOutput;
    }
    std::printf("views      %d of %s, each %dx%d, one BVH (%.1f MiB)\n", count, request.sessionFile.string().c_str(),
                cl.width, cl.height, double(tracer.buildStats().memoryBytes) / (1024.0 * 1024.0));
    std::printf("wrote      %s\n", output.c_str());
    return kExitOk;
}

} // namespace mvcl::cli
