// RayContext's clip test, out of line on purpose (RayContext.h): one baseline copy for the
// kernels of every instruction set.

#include "RayContext.h"

#include <mvcl/tracer/Ray.h>
#include <mvcl/tracer/RayQuery.h>

namespace mvcl::detail {

bool RayContext::clipsAccept(float t, uint32_t layer) const { return clipsAcceptAt(*query, ray, t, layer); }

bool clipsAcceptAt(const RayQuery &query, const Ray &ray, float t, uint32_t layer) {
    return query.acceptsPoint(ray.at(t), layer);
}

} // namespace mvcl::detail
