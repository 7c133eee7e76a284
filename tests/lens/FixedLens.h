#pragma once
// A lens for framework tests: its contribution is whatever the test sets, so composition can be
// checked without plugins.

#include <mvcl/lens/Lens.h>

#include <memory>

namespace mvcl::test {

inline const LensInfo &fixedLensInfo() {
    static const LensInfo info{"fixed", "Contributes what the test sets.", {}, kAllRayTypes, {}};
    return info;
}

class FixedLens final : public Lens {
public:
    explicit FixedLens(const LensContribution &contribution = {}, const LensRegion &region = {})
        : Lens(fixedLensInfo()), m_contribution(contribution) {
        setRegion(region);
        commit();
    }
    /// Staged like a property: takes effect on commit().
    void setContribution(const LensContribution &contribution) { m_contribution = contribution; }

protected:
    LensContribution contribute(const PropertyValues &, const LensRegion &, const LensContext &) const override {
        return m_contribution;
    }

private:
    LensContribution m_contribution;
};

inline std::shared_ptr<FixedLens> makeFixedLens(const LensContribution &contribution, const LensRegion &region) {
    return std::make_shared<FixedLens>(contribution, region);
}

} // namespace mvcl::test
