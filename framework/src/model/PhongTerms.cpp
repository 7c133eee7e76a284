#include <mvcl/model/PhongTerms.h>

#include <glm/common.hpp>

#include <algorithm>
#include <cmath>

namespace mvcl {

namespace {

float clamp01(float v) { return std::isfinite(v) ? std::clamp(v, 0.f, 1.f) : 0.f; }

} // namespace

PhongTerms phongFromMetallicRoughness(glm::vec3 baseColor, float metallic, float roughness) {
    const glm::vec3 base(clamp01(baseColor.x), clamp01(baseColor.y), clamp01(baseColor.z));
    const float m = clamp01(metallic);
    const float r = clamp01(roughness);
    PhongTerms t;
    t.diffuse = base * (1.f - m);
    t.reflectivity = m * (1.f - r);
    t.ambient = base * (1.f - t.reflectivity);
    t.specular = glm::mix(0.04f + 0.26f * (1.f - r), 1.f, m);
    t.specularColor = glm::mix(glm::vec3(1.f), base, m);
    const float rr = std::max(r, 0.05f);
    t.shininess = std::clamp(2.f / (rr * rr * rr * rr) - 2.f, 1.f, 1024.f);
    return t;
}

} // namespace mvcl
