/// clip — Viega's volumetric lens: under the lens, a box, a sphere or a half-space is cut away
/// (or only what lies inside it is kept). Coordinates are the model's world coordinates, or
/// fractions of the scene's bounding box (frame=scene, the default: 0..1 per axis, so the
/// default box is the model's +x+y+z octant). Primary rays only by default, so the surfaces left
/// standing are lit and shadowed by the whole model; rays=primary,shadow also lets the cut part
/// stop casting shadows. Visibility constraints intersect: the lens commutes and is idempotent.
/// Property table: docs/lenses.md (mvcl-render --list-lenses).

#include <mvcl/lens/LensPlugin.h>

#include <glm/common.hpp>

#include <limits>

using namespace mvcl;

namespace {

const LensInfo kClipLensInfo{
    .name = "clip",
    .description = "Cuts a box, sphere or half-space out of the model under the lens, or keeps only it.",
    .properties =
        {
            PropertyDecl::choice("volume", "box", {"box", "sphere", "halfSpace"}, "the volume that is cut"),
            PropertyDecl::choice("mode", "cut", {"cut", "keep"}, "cut the volume away, or keep only what is in it"),
            PropertyDecl::choice("frame", "scene", {"scene", "world"},
                                 "coordinates as fractions of the scene bounds (0..1 per axis) or in world units"),
            PropertyDecl::box3("box", {{0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}}, PropertySpace::World, "", "shape box"),
            PropertyDecl::point3("sphereCenter", {0.5, 0.5, 0.5}, PropertySpace::World, "", "sphere centre"),
            PropertyDecl::real("sphereRadius", 0.35, 0.0, std::numeric_limits<double>::infinity(), "",
                               "sphere radius (frame scene: a fraction of the bounds' largest side)"),
            PropertyDecl::point3("planePoint", {0.5, 0.5, 0.5}, PropertySpace::World, "",
                                 "a point on the half-space's plane"),
            PropertyDecl::vector3("planeNormal", {1.0, 0.0, 0.0}, PropertySpace::World, "",
                                  "half-space normal: the cut side is where it points"),
            PropertyDecl::choice("caps", "solid", {"none", "solid", "hatched"},
                                 "where the cut opens a closed mesh: its hollow inside, or a cap in its colour"),
        },
    .defaultRayTypes = rayTypeBit(RayType::Primary),
    .algebra = {.commutes = true, .idempotent = true},
};

class ClipLens final : public Lens {
public:
    ClipLens() : Lens(kClipLensInfo) {}

protected:
    LensContribution contribute(const PropertyValues &properties, const LensRegion &,
                                const LensContext &context) const override {
        const bool inScene = properties.choice("frame") == "scene" && !context.sceneBounds.isEmpty();
        const glm::dvec3 lower(context.sceneBounds.min), extent(context.sceneBounds.extent());
        const auto point = [&](const glm::dvec3 &p) {
            return inScene ? glm::vec3(lower + p * extent) : context.scenePoint(p, PropertySpace::World);
        };
        const Box3d box = properties.box3("box");
        const glm::vec3 center = point(properties.point3("sphereCenter")), onPlane = point(properties.point3("planePoint"));
        // A plane's normal transforms with the inverse of the fraction → world scaling.
        const glm::dvec3 normalScale = inScene ? 1.0 / glm::max(extent, 1e-30) : glm::dvec3(1.0);
        const glm::vec3 normal(properties.vector3("planeNormal") * normalScale);
        const double largestSide = inScene ? glm::max(extent.x, glm::max(extent.y, extent.z)) : 1.0;
        const float radius = float(properties.real("sphereRadius") * largestSide);
        const auto keep = ClipVolume::Keep(properties.choiceIndex("mode")); // cut, keep: enum order
        const std::string &volumeName = properties.choice("volume");
        ClipVolume volume = volumeName == "sphere"  ? ClipVolume::sphere(center, radius, keep)
                            : volumeName == "box" ? ClipVolume::box(point(box.min), point(box.max), keep)
                                                  : ClipVolume::halfSpace(normal, glm::dot(normal, onPlane), keep);
        volume.setCapStyle(ClipVolume::CapStyle(properties.choiceIndex("caps"))); // declared in enum order
        LensContribution contribution;
        for (RayQuery &query : contribution.visibility) query.addClip(volume); // "rays" chooses
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(ClipLens, kClipLensInfo)
