#pragma once
/// \file EllipseRampBatch_p.h
/// Private to LensRegion: collects the pixels of a row that need the ellipse kernel's
/// iteration (ellipseRamp4), so that it runs on full lanes and several chains at once.

#include "EllipseCoverage4_p.h"

#include <algorithm>
#include <cstddef>
#include <span>

#if defined(__SSE2__)

namespace mvcl::detail {

/// Pixels of row y that ellipseSettled4() left unsettled; flush() writes their coverage to
/// coverage[x − firstX].
class EllipseRampBatch {
public:
    EllipseRampBatch(const EllipseCoverageShape &ellipse, int y, int firstX, std::span<float> coverage)
        : m_ellipse(ellipse), m_y(_mm_set1_ps(float(y) + 0.5f)), m_firstX(firstX), m_coverage(coverage) {}

    void add(int x) {
        m_pending[m_count++] = x;
        if (m_count == kCapacity) flush();
    }

    void flush() {
        if (m_count == 0) return;
        const int chains = (m_count + 3) / 4;
        alignas(16) float centres[kCapacity];
        for (int i = 0; i < 4 * chains; ++i) centres[i] = float(m_pending[std::min(i, m_count - 1)]) + 0.5f;
        alignas(16) float ramp[kCapacity];
        switch (chains) {
        case 1: run<1>(centres, ramp); break;
        case 2: run<2>(centres, ramp); break;
        case 3: run<3>(centres, ramp); break;
        default: run<4>(centres, ramp); break;
        }
        for (int i = 0; i < m_count; ++i) m_coverage[std::size_t(m_pending[i] - m_firstX)] = ramp[i];
        m_count = 0;
    }

private:
    static constexpr int kCapacity = 16; // four chains of four lanes
    template <int Chains> void run(const float *centres, float *ramp) const {
        __m128 x[Chains], out[Chains];
        for (int c = 0; c < Chains; ++c) x[c] = _mm_load_ps(centres + 4 * c);
        ellipseRamp4(m_ellipse, x, m_y, out);
        for (int c = 0; c < Chains; ++c) _mm_store_ps(ramp + 4 * c, out[c]);
    }

    const EllipseCoverageShape &m_ellipse;
    __m128 m_y;
    int m_firstX;
    std::span<float> m_coverage;
    int m_pending[kCapacity];
    int m_count = 0;
};

} // namespace mvcl::detail

#endif
