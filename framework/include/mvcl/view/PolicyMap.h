#pragma once
/// \file PolicyMap.h
/// Per-pixel ray policies as data: a small table of distinct policies and one index per pixel.
/// Pixels covered by the same set of lenses share one entry, so policies are composed once per
/// overlap set, never per pixel. Entry 0 is the base policy.

#include <mvcl/tracer/RayPolicy.h>

#include <cstdint>
#include <vector>

namespace mvcl {

class PolicyMap {
public:
    /// Every pixel starts on `base` (entry 0).
    PolicyMap(int width, int height, const RayPolicy &base = {});

    int width() const { return m_width; }
    int height() const { return m_height; }

    /// Adds a policy and returns its index (for setPixel / fill).
    uint16_t addPolicy(const RayPolicy &policy);
    void setPixel(int x, int y, uint16_t policy) { m_index[std::size_t(y) * m_width + x] = policy; }
    uint16_t pixel(int x, int y) const { return m_index[std::size_t(y) * m_width + x]; }
    const RayPolicy &policyAt(int x, int y) const { return m_policies[pixel(x, y)]; }
    const std::vector<RayPolicy> &policies() const { return m_policies; }
    RayPolicy &policy(uint16_t index) { return m_policies[index]; }

private:
    int m_width;
    int m_height;
    std::vector<RayPolicy> m_policies;
    std::vector<uint16_t> m_index;
};

} // namespace mvcl
