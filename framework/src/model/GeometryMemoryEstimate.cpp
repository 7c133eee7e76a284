#include "GeometryMemoryEstimate_p.h"

#include <mvcl/core/Error.h>

#include <cmath>

namespace mvcl::detail {

std::string mebibytes(double bytes) { return std::to_string(std::llround(bytes / double(1 << 20))) + " MiB"; }

void refuseOverBudget(const GeometryMemoryEstimate &estimate, std::uint64_t budgetBytes, const std::string &what) {
    if (estimate.bytes <= double(budgetBytes)) return;
    throw Error("", "its geometry would need about " + mebibytes(estimate.bytes) + " (" +
                        std::to_string(std::llround(estimate.triangles)) + " triangles, " +
                        std::to_string(std::llround(estimate.vertices)) + " vertices: " + what +
                        "), more than the memory budget of " + mebibytes(double(budgetBytes)) +
                        "; refused before loading it");
}

} // namespace mvcl::detail
