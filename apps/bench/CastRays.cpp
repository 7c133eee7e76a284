#include "CastRays.h"

#include <mvcl/core/Error.h>

#include <glm/geometric.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numbers>
#include <sstream>

namespace mvcl::bench {

CastCamera CastCamera::parse(const std::string &text) {
    std::vector<double> values;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        char *end = nullptr;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || end != item.c_str() + item.size() || !std::isfinite(v))
            throw Error("--camera", "'" + item + "' is not a finite number");
        values.push_back(v);
    }
    if (values.size() != 10)
        throw Error("--camera", "expects EYE,TARGET,UP,FOVY: ten numbers, got " + std::to_string(values.size()));
    CastCamera c;
    c.eye = {values[0], values[1], values[2]};
    c.target = {values[3], values[4], values[5]};
    c.up = {values[6], values[7], values[8]};
    c.verticalFovDegrees = values[9];
    if (!(c.verticalFovDegrees > 0.0 && c.verticalFovDegrees < 180.0))
        throw Error("--camera", "the vertical field of view must be in (0, 180) degrees");
    return c;
}

std::string CastCamera::text() const {
    char buffer[512];
    std::snprintf(buffer, sizeof buffer, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", eye.x, eye.y,
                  eye.z, target.x, target.y, target.z, up.x, up.y, up.z, verticalFovDegrees);
    return buffer;
}

std::vector<Ray> castRays(const CastCamera &camera, int width, int height, const glm::dvec3 &worldOrigin) {
    const glm::dvec3 toTarget = camera.target - camera.eye;
    if (!(glm::length(toTarget) > 0.0)) throw Error("--camera", "the eye and the target are the same point");
    const glm::dvec3 forward = glm::normalize(toTarget);
    const glm::dvec3 side = glm::cross(forward, camera.up);
    if (!(glm::length(side) > 1e-12 * glm::length(camera.up)))
        throw Error("--camera", "the up vector is zero or parallel to the view direction");
    const glm::dvec3 right = glm::normalize(side);
    const glm::dvec3 up = glm::cross(right, forward);
    const double tanHalf = std::tan(0.5 * camera.verticalFovDegrees * std::numbers::pi / 180.0);
    const double aspect = double(width) / double(height);
    const glm::vec3 origin(camera.eye - worldOrigin);
    std::vector<Ray> rays;
    rays.reserve(size_t(width) * size_t(height));
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const double sx = (2.0 * (double(x) + 0.5) / double(width) - 1.0) * tanHalf * aspect;
            const double sy = (1.0 - 2.0 * (double(y) + 0.5) / double(height)) * tanHalf;
            rays.push_back({origin, glm::vec3(glm::normalize(forward + sx * right + sy * up))});
        }
    return rays;
}

} // namespace mvcl::bench
