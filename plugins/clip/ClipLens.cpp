/// clip — Viega's volumetric lens: under the lens, a box, a sphere or a half-space is cut away
/// (or only what lies inside it is kept). Coordinates are the model's world coordinates, or
/// fractions of the scene's bounding box (frame=scene, the default: 0..1 per axis, so the
/// default box is the model's +x+y+z octant); the declarations say so (spaceFrom), so the
/// framework converts them and editors such as the viewer's 3D handles place them right. The box
/// may be turned about its centre (boxRotation), and `layers` spares the layers left out: they
/// are neither cut nor capped. Primary rays only by default, so the surfaces left standing are
/// lit and shadowed by the whole model; rays=primary,shadow also lets the cut part stop casting
/// shadows. Visibility constraints intersect: the lens commutes and is idempotent.
/// Property table: docs/lenses.md (mvcl-render --list-lenses).

#include <mvcl/lens/LensPlugin.h>

#include <limits>

using namespace mvcl;

namespace {

// frame=scene reads points, boxes and lengths as fractions of the scene bounds, frame=world as
// world coordinates.
PropertyDecl framed(const PropertyDecl &decl, const char *volume) {
    return decl.withSpaceFrom("frame", {{"scene", PropertySpace::Bounds}, {"world", PropertySpace::World}})
        .whenChoice("volume", volume);
}

const LensInfo kClipLensInfo{
    .name = "clip",
    .description = "Cuts a box, sphere or half-space out of the model under the lens, or keeps only it.",
    .properties =
        {
            PropertyDecl::choice("volume", "box", {"box", "sphere", "halfSpace"}, "the volume that is cut"),
            PropertyDecl::choice("mode", "cut", {"cut", "keep"}, "cut the volume away, or keep only what is in it"),
            PropertyDecl::choice("frame", "scene", {"scene", "world"},
                                 "coordinates as fractions of the scene bounds (0..1 per axis) or in world units"),
            framed(PropertyDecl::box3("box", {{0.5, 0.5, 0.5}, {1.5, 1.5, 1.5}}, PropertySpace::Bounds, "", "shape box"),
                   "box"),
            PropertyDecl::transform("boxRotation", glm::dmat4(1.0), PropertySpace::World,
                                    "turns the box about its centre (only the rotation counts)")
                .whenChoice("volume", "box"),
            framed(PropertyDecl::point3("sphereCenter", {0.5, 0.5, 0.5}, PropertySpace::Bounds, "", "sphere centre"),
                   "sphere"),
            PropertyDecl::real("sphereRadius", 0.35, 0.0, std::numeric_limits<double>::infinity(), "",
                               "sphere radius, in the centre's frame (scene: a fraction of the bounds' largest side)")
                .whenChoice("volume", "sphere"),
            framed(PropertyDecl::point3("planePoint", {0.5, 0.5, 0.5}, PropertySpace::Bounds, "",
                                        "a point on the half-space's plane"),
                   "halfSpace"),
            framed(PropertyDecl::vector3("planeNormal", {1.0, 0.0, 0.0}, PropertySpace::Bounds, "",
                                         "half-space normal: the cut side is where it points"),
                   "halfSpace"),
            PropertyDecl::choice("caps", "solid", {"none", "solid", "hatched"},
                                 "where the cut opens a closed mesh: its hollow inside, or a cap in its colour"),
            PropertyDecl::layers("layers", kAllLayers, "the layers the cut acts on; the others stay whole"),
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
        const LensContext::OrientedBox box = context.sceneOrientedBox(
            properties.box3("box"), properties.transform("boxRotation"), properties.space("box"));
        const glm::vec3 center = context.scenePoint(properties.point3("sphereCenter"), properties.space("sphereCenter"));
        const float radius = float(context.sceneLength(properties.real("sphereRadius"), properties.space("sphereCenter")));
        const glm::vec3 onPlane = context.scenePoint(properties.point3("planePoint"), properties.space("planePoint"));
        const glm::vec3 normal = context.sceneNormal(properties.vector3("planeNormal"), properties.space("planeNormal"));
        const auto keep = ClipVolume::Keep(properties.choiceIndex("mode")); // cut, keep: enum order
        const std::string &volumeName = properties.choice("volume");
        ClipVolume volume =
            volumeName == "sphere" ? ClipVolume::sphere(center, radius, keep)
            : volumeName == "box"
                ? (box.axes == glm::dmat3(1.0) // the corners exactly as given
                       ? ClipVolume::box(glm::vec3(box.center - box.halfExtent), glm::vec3(box.center + box.halfExtent), keep)
                       : ClipVolume::orientedBox(glm::vec3(box.center), glm::vec3(box.halfExtent), glm::mat3(box.axes), keep))
                : ClipVolume::halfSpace(normal, glm::dot(normal, onPlane), keep);
        volume.setCapStyle(ClipVolume::CapStyle(properties.choiceIndex("caps"))); // declared in enum order
        volume.setLayerMask(properties.layers("layers"));
        LensContribution contribution;
        for (RayQuery &query : contribution.visibility) query.addClip(volume); // "rays" chooses
        return contribution;
    }
};

} // namespace

MVCL_LENS_PLUGIN(ClipLens, kClipLensInfo)
