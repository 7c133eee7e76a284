#include <mvcl/controller/ViewKeyframes.h>

#include <mvcl/lens/Lens.h>

namespace mvcl {

CameraKeyframe cameraKeyframeOf(const Camera &camera, const ViewCoordinates &coordinates, double seconds) {
    const LensStackCamera world = coordinates.worldFromCamera(camera);
    CameraKeyframe keyframe;
    keyframe.time = seconds;
    keyframe.eye = world.eye;
    keyframe.target = world.target;
    keyframe.up = world.up;
    keyframe.verticalFovDegrees = world.verticalFovDegrees;
    return keyframe;
}

LensKeyframe lensKeyframeOf(const Lens &lens, double seconds) {
    const std::shared_ptr<const LensSnapshot> snapshot = lens.snapshot();
    LensKeyframe keyframe;
    keyframe.time = seconds;
    const std::vector<PropertyValue> values = lens.committedValues();
    for (std::size_t i = 0; i < values.size(); ++i) keyframe.properties.emplace_back(lens.properties()[i].name, values[i]);
    keyframe.enabled = snapshot->enabled;
    const LensRegion &region = snapshot->region;
    if (region.shape() == LensRegion::Shape::Polygon) keyframe.points = region.points();
    else {
        keyframe.center = region.center();
        keyframe.size = region.size();
    }
    keyframe.feather = region.feather();
    return keyframe;
}

} // namespace mvcl
