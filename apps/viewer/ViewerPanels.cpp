// The side panel: lens stack, the selected lens (region and generated property controls),
// layers, stats, and what lies under the pointer. Every edit goes through the controller, so it
// is one undo step and reaches the render session and the recovery copy.

#include "PropertyEditor.h"
#include "Viewer.h"

#include <mvcl/io/SceneLoader.h>
#include <mvcl/lens/LensStack.h>
#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/RenderSession.h>

#include <imgui.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace mvcl::viewer {

template <class Edit>
void Viewer::edit(Edit &&change) {
    // A widget held down (a slider being dragged) is one undo step from press to release.
    if (!m_editStepOpen && ImGui::IsAnyItemActive()) {
        m_controller->beginEditStep();
        m_editStepOpen = true;
    }
    try {
        change();
    } catch (const Error &e) {
        report(e.what());
    }
}

void Viewer::drawUi() {
    if (!m_player) forwardInput(); // a playing animation owns the view until it ends
    drawImage();
    drawLensOverlays();
    drawPanels();
    drawHelpOverlay();
    drawOpenPopup();
    drawRecoveryOffer();
    drawMessages();
    if (m_editStepOpen && !ImGui::IsAnyItemActive()) {
        m_controller->endEditStep();
        m_editStepOpen = false;
    }
}

void Viewer::drawPanels() {
    ImGui::SetNextWindowPos(ImVec2(m_viewScreenSize.x, 0.f), ImGuiCond_Always);
    ImGui::SetNextWindowSize(ImVec2(m_panelWidth, m_viewScreenSize.y), ImGuiCond_Always);
    ImGui::Begin("mvcl", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);
    ImGui::TextDisabled("%s  (F1: help)", describeSources(m_controller->sceneSources()).c_str());
    if (ImGui::CollapsingHeader("Views", m_document->viewCount() > 1 ? ImGuiTreeNodeFlags_DefaultOpen : 0)) drawViewsPanel();
    if (ImGui::CollapsingHeader("Lenses", ImGuiTreeNodeFlags_DefaultOpen)) drawLensStackPanel();
    if (ImGui::CollapsingHeader("Selected lens", ImGuiTreeNodeFlags_DefaultOpen)) drawLensPanel();
    if (ImGui::CollapsingHeader("Layers", ImGuiTreeNodeFlags_DefaultOpen)) drawLayersPanel();
    if (ImGui::CollapsingHeader("Under the pointer", ImGuiTreeNodeFlags_DefaultOpen)) drawPickPanel();
    if (ImGui::CollapsingHeader("Depth histogram")) drawHistogramPanel();
    if (ImGui::CollapsingHeader("Animation")) drawAnimationPanel();
    // Every frame, open or not, so that the curve has every pass when the panel opens.
    m_convergence.add(m_controller->renderSession().convergence(), m_controller->renderSession().passCount());
    if (ImGui::CollapsingHeader("Stats", ImGuiTreeNodeFlags_DefaultOpen)) drawStatsPanel();
    ImGui::End();
}

void Viewer::drawViewsPanel() {
    int layout = int(m_document->layout());
    const char *const names[] = {"1", "1x2", "2x1", "2x2"};
    for (int i = 0; i < 4; ++i) {
        if (i > 0) ImGui::SameLine();
        if (ImGui::RadioButton(names[i], &layout, i)) setLayout(ViewLayout(i));
    }
    const int focus = m_document->focusedView();
    ImGui::Text("focused: view %d of %d (Tab: next)", focus, m_document->viewCount());
    // Links of the focused view with each other view.
    for (int other = 0; other < m_document->viewCount(); ++other) {
        if (other == focus) continue;
        ImGui::PushID(other);
        ImGui::Text("link with view %d:", other);
        for (LinkAspect aspect : {LinkAspect::Camera, LinkAspect::Lenses, LinkAspect::Layers}) {
            ImGui::SameLine();
            bool linked = m_document->isLinked(focus, other, aspect);
            if (ImGui::Checkbox(linkAspectName(aspect), &linked))
                edit([&] { linked ? m_document->link(focus, other, aspect) : m_document->unlink(focus, other, aspect); });
        }
        ImGui::PopID();
    }
    bool compare = m_controller->isCompareEnabled();
    if (ImGui::Checkbox("compare A | B", &compare)) edit([&] { m_controller->setCompareEnabled(compare); });
    if (compare) {
        ImGui::SameLine();
        int side = int(m_controller->compareSide());
        if (ImGui::RadioButton("edit A", &side, 0)) m_controller->setCompareSide(CompareSide::Left);
        ImGui::SameLine();
        if (ImGui::RadioButton("edit B", &side, 1)) m_controller->setCompareSide(CompareSide::Right);
        float divider = m_controller->compareDivider();
        if (ImGui::SliderFloat("divider", &divider, 0.f, 1.f)) edit([&] { m_controller->setCompareDivider(divider); });
    }
}

void Viewer::drawLensStackPanel() {
    const LensStack &stack = m_controller->lensStack();
    // Top of the stack first, as the lenses lie over the image.
    for (int i = stack.size() - 1; i >= 0; --i) {
        const Lens &lens = *stack.lens(i);
        ImGui::PushID(i);
        bool enabled = lens.isEnabled();
        if (ImGui::Checkbox("##enabled", &enabled)) edit([&] { m_controller->setLensEnabled(i, enabled); });
        ImGui::SameLine();
        const std::string name = std::to_string(i) + "  " + lens.typeName() + (lens.label().empty() ? "" : "  '" + lens.label() + "'");
        if (ImGui::Selectable(name.c_str(), m_controller->selectedLens() == i, 0, ImVec2(ImGui::GetContentRegionAvail().x - 90.f * m_contentScale, 0.f)))
            m_controller->setSelectedLens(i);
        ImGui::SameLine();
        if (ImGui::ArrowButton("up", ImGuiDir_Up) && i + 1 < stack.size()) edit([&] { m_controller->raiseLens(i); });
        ImGui::SameLine();
        if (ImGui::ArrowButton("down", ImGuiDir_Down) && i > 0) edit([&] { m_controller->lowerLens(i); });
        ImGui::SameLine();
        if (ImGui::SmallButton("x")) edit([&] { m_controller->removeLens(i); });
        ImGui::PopID();
    }
    if (stack.isEmpty()) ImGui::TextDisabled("no lenses yet");
    if (ImGui::BeginCombo("##add", "add a lens ...")) {
        for (const std::string &type : m_controller->lensRegistry().lensTypes())
            if (ImGui::Selectable(type.c_str())) edit([&] { m_controller->addLens(type, {0.5f, 0.5f}); });
        ImGui::EndCombo();
    }
    const int selected = m_controller->selectedLens();
    ImGui::SameLine();
    ImGui::BeginDisabled(selected < 0);
    if (ImGui::Button("duplicate")) edit([&] { m_controller->duplicateLens(selected); });
    ImGui::EndDisabled();
    ImGui::BeginDisabled(!m_controller->canUndo());
    if (ImGui::Button("undo")) edit([&] { m_controller->undo(); });
    ImGui::EndDisabled();
    ImGui::SameLine();
    ImGui::BeginDisabled(!m_controller->canRedo());
    if (ImGui::Button("redo")) edit([&] { m_controller->redo(); });
    ImGui::EndDisabled();
}

void Viewer::drawLensPanel() {
    const int index = m_controller->selectedLens();
    if (index < 0 || index >= m_controller->lensCount()) {
        ImGui::TextDisabled("click a lens to select it");
        return;
    }
    const Lens &lens = *m_controller->lensStack().lens(index);
    ImGui::Text("%s", lens.typeName().c_str());
    ImGui::TextWrapped("%s", lens.info().description.c_str());

    // The region: shape, centre and size in normalised image coordinates, feather in pixels.
    LensRegion region = lens.region();
    bool regionChanged = false;
    if (region.shape() != LensRegion::Shape::Polygon) {
        glm::vec2 center = region.center(), size = region.size();
        if (ImGui::DragFloat2("center", &center.x, 0.002f, -1.f, 2.f)) {
            region.setCenter(center);
            regionChanged = true;
        }
        if (ImGui::DragFloat2("size", &size.x, 0.002f, 0.01f, 2.f)) {
            region.setSize(glm::max(size, glm::vec2(0.01f)));
            regionChanged = true;
        }
    }
    float feather = region.feather();
    if (ImGui::SliderFloat("feather", &feather, 0.f, 40.f, "%.1f px")) {
        region.setFeather(feather);
        regionChanged = true;
    }
    float outline = region.outlineWidth();
    if (ImGui::SliderFloat("outline", &outline, 0.f, 8.f, "%.1f px")) {
        region.setOutlineWidth(outline);
        regionChanged = true;
    }
    if (regionChanged) edit([&] { m_controller->setLensRegion(index, region); });
    bool follows = m_controller->pointerFollowingLens() == index;
    if (ImGui::Checkbox("follow the pointer (P)", &follows)) m_controller->setPointerFollowingLens(follows ? index : -1);
    drawFitButtons(index);

    // The declared properties: one generated control each, no per-lens code.
    // Properties not in use (clip's sphere while volume=box) are dimmed, still editable.
    const LayerTable &layers = m_controller->scene().layers;
    const std::vector<PropertyValue> committed = lens.committedValues();
    const PropertyValues read(lens.properties(), committed);
    for (const PropertyDecl &decl : lens.properties()) {
        PropertyValue value = lens.property(decl.name);
        ImGui::PushID(decl.name.c_str());
        const bool used = read.isUsed(decl.name);
        if (!used) ImGui::PushStyleVar(ImGuiStyleVar_Alpha, 0.5f * ImGui::GetStyle().Alpha);
        if (editProperty(decl, value, layers))
            edit([&] { m_controller->setLensProperty(index, decl.name, value.toString()); });
        if (!used) ImGui::PopStyleVar();
        ImGui::PopID();
    }
}

void Viewer::drawFitButtons(int index) {
    // Only lenses with a box or sphere in use can be fitted (the B key fits to the object
    // under the pointer).
    const std::vector<GizmoShape> shapes = m_controller->gizmoShapes(index);
    if (std::ranges::none_of(shapes, [](const GizmoShape &s) {
            return s.decl.kind == GizmoDecl::Kind::Box || s.decl.kind == GizmoDecl::Kind::Sphere;
        }))
        return;
    if (ImGui::Button("fit to all")) edit([&] { m_controller->fitLens(index, LensFit::All); });
    ImGui::SameLine();
    if (ImGui::Button("fit to layer")) edit([&] { m_controller->fitLens(index, LensFit::Layer, m_fitLayer); });
    ImGui::SameLine();
    ImGui::SetNextItemWidth(60.f * m_contentScale);
    ImGui::InputInt("##fitLayer", &m_fitLayer);
    m_fitLayer = std::clamp(m_fitLayer, 0, kMaxLayers - 1);
}

void Viewer::drawLayersPanel() {
    for (const Layer &layer : m_controller->scene().layers.layers()) {
        ImGui::PushID(layer.id);
        const glm::vec3 c = layer.color;
        ImGui::ColorButton("##colour", ImVec4(c.x, c.y, c.z, 1.f), ImGuiColorEditFlags_NoTooltip);
        ImGui::SameLine();
        bool visible = m_controller->layerVisibility(layer.id) == LayerVisibility::Visible;
        const std::string label = std::to_string(layer.id) + "##visible";
        if (ImGui::Checkbox(label.c_str(), &visible))
            edit([&] { m_controller->setLayerVisibility(layer.id, visible ? LayerVisibility::Visible : LayerVisibility::Hidden); });
        // The name, editable: renamed when the field is left or Enter pressed (one undo step).
        ImGui::SameLine();
        char name[128];
        std::snprintf(name, sizeof name, "%s", m_controller->layerName(layer.id).c_str());
        ImGui::SetNextItemWidth(-1.f);
        ImGui::InputText("##name", name, sizeof name);
        if (ImGui::IsItemDeactivatedAfterEdit()) {
            const int id = layer.id;
            const std::string renamed = name;
            edit([&] { m_controller->setLayerName(id, renamed); });
        }
        ImGui::PopID();
    }
}

const PolicyMap &Viewer::pickingMap() {
    const LensStack &stack = m_controller->lensStack();
    std::vector<const void *> snapshots;
    for (const auto &lens : stack.lenses()) snapshots.push_back(lens->snapshot().get());
    const glm::ivec2 size = m_controller->viewSize();
    if (!m_pickMap || m_pickMap->width() != size.x || m_pickMap->height() != size.y || snapshots != m_pickSnapshots ||
        m_pickLayers != m_controller->visibleLayers()) {
        m_pickMap = stack.compose(m_controller->basePolicy(), size.x, size.y);
        m_pickSnapshots = std::move(snapshots);
        m_pickLayers = m_controller->visibleLayers();
    }
    return *m_pickMap;
}

void Viewer::drawPickPanel() {
    if (m_pointer.x < 0.f) {
        ImGui::TextDisabled("move the pointer over the image");
        return;
    }
    // The ray of the pixel under its composed policy: what a lens hides cannot be picked.
    const PickResult p = pick(m_controller->tracer(), m_controller->camera(), pickingMap(), int(m_pointer.x), int(m_pointer.y));
    ImGui::Text("pixel %d, %d", int(m_pointer.x), int(m_pointer.y));
    if (!p.hit) {
        ImGui::TextDisabled("nothing: the background");
        return;
    }
    ImGui::Text("layer %d  %s", p.layer, m_controller->layerName(p.layer).c_str());
    ImGui::Text("object %s", p.objectName.c_str());
    if (!p.nodeName.empty() || !p.meshName.empty())
        ImGui::Text("node %s, mesh %s", p.nodeName.c_str(), p.meshName.c_str());
    ImGui::Text("material %u  %s", p.material, p.materialName.c_str());
    ImGui::Text("distance %.6g", double(p.distance));
    ImGui::Text("world %.6g, %.6g, %.6g", p.worldPosition.x, p.worldPosition.y, p.worldPosition.z);
}

void Viewer::stopHistogramWorker() {
    if (m_histogramWorker.joinable()) {
        m_histogramWorker.request_stop();
        m_histogramWorker.join();
    }
    std::lock_guard lock(m_histogramMutex);
    m_histogram.reset();
    m_histogramBusy = false;
}

void Viewer::drawHistogramPanel() {
    const int index = m_controller->selectedLens();
    if (index < 0 || m_controller->lensStack().lens(index)->typeName() != "layer") {
        ImGui::TextDisabled("select a layer lens");
        return;
    }
    bool busy;
    std::optional<DepthHistogram> histogram;
    {
        std::lock_guard lock(m_histogramMutex);
        busy = m_histogramBusy;
        if (m_histogramLens == index) histogram = m_histogram;
    }
    ImGui::BeginDisabled(busy);
    if (ImGui::Button(busy ? "computing ..." : "depth histogram under the lens")) {
        const glm::ivec2 size = m_controller->viewSize();
        // The request is built here (it reads the lenses); the rays are traced on a worker.
        const Tracer &tracer = m_controller->tracer();
        DepthHistogramRequest request = depthHistogramRequest(tracer, m_controller->lensStack(), index,
                                                              m_controller->basePolicy(), m_controller->camera(),
                                                              size.x, size.y);
        stopHistogramWorker();
        {
            std::lock_guard lock(m_histogramMutex);
            m_histogramLens = index;
            m_histogramBusy = true;
        }
        m_histogramWorker = std::jthread([this, &tracer, request](std::stop_token stop) {
            DepthHistogram result = computeDepthHistogram(tracer, request, stop);
            std::lock_guard lock(m_histogramMutex);
            m_histogram = std::move(result);
            m_histogramBusy = false;
        });
    }
    ImGui::EndDisabled();
    if (!histogram) return;
    if (histogram->isEmpty()) {
        ImGui::TextDisabled("no surface under the lens");
        return;
    }
    std::vector<float> counts(histogram->counts.begin(), histogram->counts.end());
    ImGui::PlotHistogram("##depths", counts.data(), int(counts.size()), 0, nullptr, 0.f, FLT_MAX,
                         ImVec2(ImGui::GetContentRegionAvail().x, 70.f * m_contentScale));
    ImGui::Text("%.4g .. %.4g, %u rays, %.1f ms", double(histogram->tNear), double(histogram->tFar),
                histogram->raysSampled, histogram->milliseconds);
    ImGui::TextDisabled("click a suggested d to set it:");
    for (const DepthSuggestion &s : histogram->suggestions) {
        char label[96];
        std::snprintf(label, sizeof label, "d = %.4g  (%u rays, layer %d to %d)", double(s.distance), s.raysSeparated,
                      s.layerBefore, s.layerAfter);
        if (ImGui::SmallButton(label))
            edit([&] { m_controller->setLensProperty(index, "distance", std::to_string(s.distance)); });
    }
}

void Viewer::drawStatsPanel() {
    RenderSession &session = m_controller->renderSession();
    const RenderPassStats pass = session.lastPass();
    const ConvergenceStats c = session.convergence();
    std::vector<double> sorted(m_frameTimes.begin(), m_frameTimes.end());
    std::sort(sorted.begin(), sorted.end());
    ImGui::Text("UI frame %.1f ms (median %.1f, worst %.1f of the last %zu)", m_lastFrameMs,
                sorted.empty() ? 0.0 : sorted[sorted.size() / 2], sorted.empty() ? 0.0 : sorted.back(), sorted.size());
    ImGui::Text("view %d x %d px, %d lenses", m_controller->viewSize().x, m_controller->viewSize().y, m_controller->lensCount());
    ImGui::Text("pass %s%s: %.1f ms, %llu px, %.2f Mrays/s", passKindName(pass.kind),
                pass.wasCancelled ? " (cancelled)" : "", pass.milliseconds, (unsigned long long)pass.pixelsTraced,
                pass.traceMilliseconds > 0 ? double(pass.rays.total()) / (pass.traceMilliseconds * 1e3) : 0.0);
    if (pass.kind == PassKind::Preview) ImGui::Text("preview at 1/%d resolution", pass.resolutionDivider);
    ImGui::Text("samples %d min, %.1f mean, %d max per pixel", c.minSamples, c.meanSamples, c.maxSamples);
    ImGui::Text("estimated error %.4f mean, %.4f max%s", c.meanError, c.maxError, c.isConverged ? "  (converged)" : "");
    drawConvergenceCurve();
    for (const LensCost &cost : pass.perLens)
        ImGui::Text("  lens %d '%s': %llu px, %.1f ms", cost.index, cost.label.c_str(), (unsigned long long)cost.pixels,
                    cost.milliseconds);

    RenderSettings settings = m_controller->renderSettings();
    int mode = int(settings.sampling);
    const char *modes[] = {"fixed", "progressive", "adaptive"};
    bool changed = ImGui::Combo("sampling", &mode, modes, 3);
    changed |= ImGui::SliderInt("max spp", &settings.maxSamplesPerPixel, 1, 4096, "%d", ImGuiSliderFlags_Logarithmic);
    changed |= ImGui::SliderFloat("target error", &settings.targetError, 0.f, 0.1f, "%.4f", ImGuiSliderFlags_Logarithmic);
    if (changed) {
        settings.sampling = SamplingMode(mode);
        try {
            m_controller->setRenderSettings(settings);
        } catch (const Error &e) {
            report(e.what());
        }
    }
}

void Viewer::drawConvergenceCurve() {
    // The image's estimated relMSE (no reference) against time since the last restart: what
    // more waiting buys. Log scale, the time axis even (ConvergenceHistory resamples it).
    const std::vector<float> curve = m_convergence.log10ErrorOverTime(96);
    if (curve.empty()) {
        ImGui::TextDisabled("error curve: from two samples a pixel on");
        return;
    }
    const ConvergenceHistory::Point &last = m_convergence.points().back();
    const auto [low, high] = std::minmax_element(curve.begin(), curve.end());
    char overlay[96];
    std::snprintf(overlay, sizeof overlay, "relMSE %.2g after %.1f s", last.relativeMse, last.seconds);
    ImGui::PlotLines("##error", curve.data(), int(curve.size()), 0, overlay, *low - 0.1f, *high + 0.1f,
                     ImVec2(ImGui::GetContentRegionAvail().x, 60.f * m_contentScale));
    ImGui::TextDisabled("est. relMSE %.2g .. %.2g (log), 0 .. %.1f s", std::pow(10.0, double(*low)),
                        std::pow(10.0, double(*high)), last.seconds);
}

void Viewer::drawOpenPopup() {
    if (m_openPopupRequested) {
        ImGui::OpenPopup("Open");
        m_openPopupRequested = false;
    }
    if (!ImGui::BeginPopupModal("Open", nullptr, ImGuiWindowFlags_AlwaysAutoResize)) return;
    ImGui::TextUnformatted("A model (.gltf, .glb, builtin:NAME) or a session (.json):");
    char path[1024];
    std::snprintf(path, sizeof path, "%s", m_openPath.c_str());
    if (ImGui::IsWindowAppearing()) ImGui::SetKeyboardFocusHere();
    const bool entered = ImGui::InputText("##path", path, sizeof path, ImGuiInputTextFlags_EnterReturnsTrue);
    m_openPath = path;
    if (entered || ImGui::Button("open")) {
        openFile(m_openPath);
        ImGui::CloseCurrentPopup();
    }
    ImGui::SameLine();
    if (ImGui::Button("cancel")) ImGui::CloseCurrentPopup();
    ImGui::EndPopup();
}

} // namespace mvcl::viewer
