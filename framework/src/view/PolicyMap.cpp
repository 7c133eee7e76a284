#include <mvcl/view/PolicyMap.h>

#include <mvcl/core/Error.h>

namespace mvcl {

PolicyMap::PolicyMap(int width, int height, const RayPolicy &base)
    : m_width(width), m_height(height), m_policies{base},
      m_index(std::size_t(width) * std::size_t(height), 0) {}

uint16_t PolicyMap::addPolicy(const RayPolicy &policy) {
    if (m_policies.size() >= 0xffff) throw Error("", "too many distinct ray policies in one view");
    m_policies.push_back(policy);
    return uint16_t(m_policies.size() - 1);
}

} // namespace mvcl
