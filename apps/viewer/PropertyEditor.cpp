#include "PropertyEditor.h"

#include <mvcl/core/Error.h>

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace mvcl::viewer {

namespace {

/// A finite range for sliders: declared bounds where finite, a span around the value elsewhere.
void sliderRange(const PropertyDecl &decl, double value, double &lo, double &hi) {
    lo = std::isfinite(decl.minimum) ? decl.minimum : std::min(0.0, value) - 10.0;
    hi = std::isfinite(decl.maximum) ? decl.maximum : std::max(lo + 1.0, value * 2.0 + 10.0);
}

void tooltip(const PropertyDecl &decl) {
    if (!ImGui::IsItemHovered()) return;
    const std::string range = decl.rangeText();
    ImGui::SetTooltip("%s\n%s", decl.doc.c_str(), range.c_str());
}

struct MaskBit {
    int bit;
    const char *name;
};

/// A collapsible list of checkboxes, one per bit.
bool editMask(const char *label, uint32_t &mask, const std::vector<MaskBit> &bits) {
    bool changed = false;
    if (ImGui::TreeNode(label)) {
        for (const MaskBit &b : bits) {
            bool on = (mask >> b.bit) & 1u;
            if (ImGui::Checkbox(b.name, &on)) {
                mask = on ? mask | (1u << b.bit) : mask & ~(1u << b.bit);
                changed = true;
            }
        }
        ImGui::TreePop();
    }
    return changed;
}

} // namespace

bool editProperty(const PropertyDecl &decl, PropertyValue &value, const LayerTable &layers) {
    const char *label = decl.name.c_str();
    bool changed = false;
    switch (decl.type) {
    case PropertyType::Bool: {
        bool v = value.toBool();
        if ((changed = ImGui::Checkbox(label, &v))) value = PropertyValue::boolean(v);
        break;
    }
    case PropertyType::Int: {
        double lo, hi;
        sliderRange(decl, value.toInt(), lo, hi);
        int v = value.toInt();
        if ((changed = ImGui::SliderInt(label, &v, int(lo), int(hi), "%d", ImGuiSliderFlags_AlwaysClamp)))
            value = PropertyValue::integer(v);
        break;
    }
    case PropertyType::Real: {
        double lo, hi;
        sliderRange(decl, value.toReal(), lo, hi);
        double v = value.toReal();
        const std::string format = decl.unit.empty() ? "%.4g" : "%.4g " + decl.unit;
        if ((changed = ImGui::SliderScalar(label, ImGuiDataType_Double, &v, &lo, &hi, format.c_str(),
                                           ImGuiSliderFlags_AlwaysClamp)))
            value = PropertyValue::real(std::clamp(v, decl.minimum, decl.maximum));
        break;
    }
    case PropertyType::Color: {
        glm::vec3 c = value.toColor();
        float rgb[3] = {c.x, c.y, c.z};
        if ((changed = ImGui::ColorEdit3(label, rgb, ImGuiColorEditFlags_Float | ImGuiColorEditFlags_HDR))) {
            for (float &component : rgb) component = float(std::clamp(double(component), decl.minimum, decl.maximum));
            value = PropertyValue::color({rgb[0], rgb[1], rgb[2]});
        }
        break;
    }
    case PropertyType::Choice: {
        const std::string current = value.toChoice();
        if (ImGui::BeginCombo(label, current.c_str())) {
            for (const std::string &choice : decl.choices)
                if (ImGui::Selectable(choice.c_str(), choice == current)) {
                    value = PropertyValue::choice(choice);
                    changed = choice != current;
                }
            ImGui::EndCombo();
        }
        break;
    }
    case PropertyType::LayerSet: {
        uint32_t mask = value.toLayerSet();
        std::vector<MaskBit> bits;
        for (const Layer &layer : layers.layers()) bits.push_back({layer.id, layer.name.c_str()});
        if ((changed = editMask(label, mask, bits))) value = PropertyValue::layerSet(mask);
        break;
    }
    case PropertyType::RayTypeSet: {
        uint32_t mask = value.toRayTypeSet();
        const std::vector<MaskBit> bits = {{0, "primary"}, {1, "shadow"}, {2, "reflection"}, {3, "refraction"}};
        if ((changed = editMask(label, mask, bits))) value = PropertyValue::rayTypeSet(uint8_t(mask));
        break;
    }
    case PropertyType::Point3:
    case PropertyType::Vector3:
    case PropertyType::Box3:
    case PropertyType::Transform: {
        // Typed in the property's own text form, applied on Enter when it parses and validates.
        std::array<char, 512> buffer{};
        const std::string text = value.toString();
        text.copy(buffer.data(), buffer.size() - 1);
        if (ImGui::InputText(label, buffer.data(), buffer.size(), ImGuiInputTextFlags_EnterReturnsTrue)) {
            try {
                value = decl.parse(buffer.data());
                changed = true;
            } catch (const Error &) { // the old value stays; the tooltip gives the form
            }
        }
        break;
    }
    }
    tooltip(decl);
    return changed;
}

} // namespace mvcl::viewer
