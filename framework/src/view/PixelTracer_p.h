#pragma once
// Private: the per-pixel kernel shared by Renderer (one-shot frames) and RenderSession
// (incremental, progressive, adaptive). Sample k of pixel (x, y) depends only on (x, y, k,
// seed) and the pixel's policy terms, so any subset of pixels and samples can be traced in any
// order, on any thread, and a pixel's sum over k = 0, 1, … is the same bit for bit.

#include <mvcl/lens/PolicyCost.h>
#include <mvcl/lens/PolicyMap.h>
#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/IntegratorPlan.h>
#include <mvcl/tracer/RayCounters.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/tracer/WhittedIntegrator.h>
#include <mvcl/view/Camera.h>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <bit>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

namespace mvcl::detail {

/// Position of sample k inside pixel (x, y), in [0, 1)²: sample 0 is the pixel centre (a
/// one-sample image is sharp and stable while a lens is dragged); samples 1, 2, … follow the
/// R2 sequence (a 2-D Kronecker sequence, well spread for any prefix length, which is what
/// progressive rendering needs) rotated per pixel by a hash of (x, y, seed).
glm::vec2 sampleOffset(int x, int y, uint32_t k, uint32_t seed);

/// sampleOffset() of one pixel with its rotation computed once: a pixel's samples in a pass
/// hash the pixel once, not once per sample. Bit for bit sampleOffset(x, y, k, seed).
class PixelSequence {
public:
    PixelSequence() = default; ///< unrotated (filled in later)
    PixelSequence(int x, int y, uint32_t seed);
    glm::vec2 offset(uint32_t k) const;

private:
    double m_u0 = 0.5, m_v0 = 0.5; ///< 0.5 + the pixel's rotation, per axis
};

/// Running sums of one pixel's samples, and runs of them whose differences estimate the pixel's
/// error (adaptive sampling, and the image's estimated relMSE). The blocks: the first 2^m
/// samples and the rest, 2^m the largest power of two below the count (at a power of two, the
/// two halves). Each block is a run of consecutive points of the pixel's R2 sequence, itself
/// well spread, so their difference measures the error of the mean with the sequence's
/// cancellation in it; interleaved halves (even and odd samples) fill each other's gaps, and
/// their difference came out 1.5–9× the true error (docs/benchmarks.md). How much of the error
/// cancels depends on the count, so every estimate is scaled to the expected squared error by
/// a table per count (BlockEstimateScale_p.h), computed for pixels crossed by an edge.
struct PixelSamples {
    glm::vec3 sum{0.f};
    /// Sums of the first 2^m, 2^(m−1) and 3·2^(m−2) samples, 2^m the largest power of two not
    /// above count (0 while there is none).
    glm::vec3 prefixSum{0.f}, halfPrefixSum{0.f}, threeQuarterSum{0.f};
    /// At count = 2^m, the sum of the first 2^(m−2) samples (the earlier look needs it there
    /// only); from 3·2^(m−1) samples on, the sum of the first 3·2^(m−1), the next level's three
    /// quarters. One slot for both keeps a pixel's state at 68 bytes.
    glm::vec3 quarterOrNextThreeQuarterSum{0.f};
    uint32_t count = 0;
    uint32_t rays = 0; ///< rays traced for these samples: what one more sample costs, on average

    glm::vec3 mean() const { return count ? sum / float(count) : glm::vec3(0.f); }
    /// Adds the value of sample k to the sums; samples come in order (k = 0, 1, …, as
    /// count counts them, sample 0 into default sums), and advancing count is the caller's.
    void add(uint32_t k, const glm::vec3 &value) {
        sum += value;
        const uint32_t n = k + 1;
        if ((k & n) == 0) { // n a power of two
            // Sample 0 goes into zeroed sums (a pixel at count 0 is a fresh PixelSamples), so
            // the three moves would copy zeros over zeros: skipped in one-sample passes.
            if (k != 0) {
                threeQuarterSum = quarterOrNextThreeQuarterSum;
                quarterOrNextThreeQuarterSum = halfPrefixSum;
                halfPrefixSum = prefixSum;
            }
            prefixSum = sum;
        } else if (n % 3 == 0 && std::has_single_bit(n / 3)) { // three quarters of the next power of two
            quarterOrNextThreeQuarterSum = sum;
        }
    }
    /// Σ_c σ_c / √(ε + I_r + I_g + I_b), I the mean and σ_c² the blocks' variance of the mean
    /// per channel, (A_c − B_c)²·ab/n² (A the mean of the first block, a samples, B of the
    /// second), scaled per count; +∞ with fewer than two samples. The standard error of the
    /// mean, relative to its brightness. What adaptive sampling decides by, so from 4 samples on
    /// σ_c² is at least the earlier look's: the same estimate from the two halves of the first
    /// p samples (p the largest power of two below the count), scaled to n samples. One
    /// difference of two means is a single degree of freedom, below a tenth of its expectation a
    /// quarter of the time, and a pixel whose estimate happened to come out low would wait
    /// behind the others with its error.
    float relativeError() const;
    /// Which of a pixel's estimates its share of the image's estimated relMSE comes from.
    enum class ImageEstimate {
        /// Every pixel sampled alike (fixed or progressive): from 4 samples on, the mean of the
        /// blocks' estimate and the later look's (the two halves of the second half of the first
        /// 2^m samples, 2^m the largest power of two not above the count, scaled to n samples):
        /// two degrees of freedom.
        EveryPixelAlike,
        /// Adaptive sampling: from 4 samples on, the later look alone. The blocks and the earlier
        /// look are what it decides by, and a pixel it leaves behind because they came out low
        /// would take that luck into the image's estimate (from the blocks alone, 0.61–0.69× of
        /// the true error in the images measured); the later look is not among what decided.
        AfterAdaptiveDecisions,
    };
    /// The squared error of mean() relative to its value, as the image's relMSE counts it: per
    /// channel σ_c² over (mean² + 0.01), averaged over the channels, σ_c² from `source`.
    /// Meaningful with two samples or more (0 below).
    float relativeMse(ImageEstimate source) const;

private:
    /// Per channel, the variance of the mean from the two blocks (count ≥ 2).
    glm::vec3 blockVariance() const;
    /// The variance of the mean of count samples from the two halves of the first p (p the
    /// largest power of two below count; count ≥ 4).
    glm::vec3 earlierBlockVariance() const;
    /// The same from the two halves of the second half of the first 2^m samples (2^m the
    /// largest power of two not above count; count ≥ 4).
    glm::vec3 laterBlockVariance() const;
};

/// Traces samples of pixels under a policy map and charges rays, pixels and time to its
/// policies. One per worker and pass: not thread-safe, cheap to make.
class PixelTracer {
public:
    /// Plans every policy of `map` once (WhittedIntegrator::plan with `stages`).
    PixelTracer(const WhittedIntegrator &integrator, const Camera &camera, const PolicyMap &map,
                uint32_t seed, StageSelection stages);

    /// Adds samples [samples.count, endSample) of pixel (x, y) to `samples`, in order.
    void addSamples(int x, int y, uint32_t endSample, PixelSamples &samples);
    /// Side of the pixel blocks whose primary rays share a packet (Tracer::kPacketSize = 4 × 4).
    static constexpr int kBlockSide = 4;
    /// addSamples() for each pixel of the block [x0, x1) × [y0, y1) (at most kBlockSide square),
    /// `endSample` one per pixel, row by row; the sums of pixel (x, y) at
    /// samples[(y − y0) · rowStride + (x − x0)] (the session's own rows: no copies in and out).
    /// Where every pixel of the block has one and the same policy (no feathered edge), sample k
    /// of the pixels that take it goes through the tracer as one packet of primary rays;
    /// otherwise pixel by pixel. Same sums bit for bit as addSamples() pixel by pixel.
    void addBlockSamples(int x0, int y0, int x1, int y1, const uint32_t *endSample, PixelSamples *samples,
                         std::size_t rowStride);
    /// One sample through the continuous raster position `position` under the policies of
    /// pixel (x, y) (previews: one ray per block of pixels).
    glm::vec3 sampleAt(int x, int y, const glm::vec2 &position);

    /// Call where the policy run ends (end of a tile row) so time is charged to it.
    void endRun();
    RayCounters rays() const;
    uint64_t samplesTaken() const { return m_samples; }
    /// Adds this tracer's per-policy costs into `costs` (resized to the map's policy count).
    void addCostsTo(std::vector<PolicyCost> &costs) const;

private:
    using Clock = std::chrono::steady_clock;
    glm::vec3 traceTerms(int x, int y, const glm::vec2 &position);
    void chargeRun(int policy);
    /// The one policy of every pixel of the block, or −1 (a feathered edge, or policies differ).
    int blockPolicy(int x0, int y0, int x1, int y1) const;
    /// addBlockSamples() for a whole block (kBlockSide square) of one policy whose pixels all
    /// take samples [begin, end): one packet per sample, lane i pixel i.
    void addUniformBlockSamples(int x0, int y0, uint32_t begin, uint32_t end, int shared, PixelSamples *samples,
                                std::size_t rowStride);
    /// Traces the first `lanes` lanes of m_lanes under policy `shared` and adds each value to its
    /// pixel's sums; returns the rays traced.
    uint64_t traceLanes(int lanes, int shared);
    /// Whether every ray of the whole block at (x0, y0) misses everything under `policy` and shows
    /// the same value (see m_footprint and MissAnswer).
    bool blockMisses(int x0, int y0, int policy, bool shaped) const;

    /// A packet of primary rays being filled by addBlockSamples(): kept here, not on the stack
    /// of each call, so that a block does not construct 16 rays, hits and counters anew.
    struct PacketLanes {
        std::array<glm::vec2, Tracer::kPacketSize> positions;
        std::array<Ray, Tracer::kPacketSize> rays;
        std::array<Hit, Tracer::kPacketSize> hits;
        std::array<glm::vec3, Tracer::kPacketSize> values;
        /// Each lane's rays since the tracer was made: radianceFromHits() adds to them, so
        /// they are never cleared; a sample's rays are the growth of its lane's total.
        std::array<RayCounters, Tracer::kPacketSize> counters;
        std::array<uint64_t, Tracer::kPacketSize> totals{}; ///< counters[j].total() after the last packet
        std::array<PixelSamples *, Tracer::kPacketSize> sums; ///< the pixel each lane's sample adds to
        std::array<uint32_t, Tracer::kPacketSize> sample;     ///< the lane's sample index k
    };
    PacketLanes m_lanes;

    const WhittedIntegrator &m_integrator;
    const Camera &m_camera;
    const PolicyMap &m_map;
    uint32_t m_seed;
    std::vector<IntegratorPlan> m_plans; ///< per policy of m_map
    /// What a primary ray that meets nothing gives under a policy, where that is one value for
    /// all of them (WhittedIntegrator::plainMissRadiance); per policy of m_map.
    struct MissAnswer {
        bool isPlain = false;
        glm::vec3 radiance{0.f};
        RayCounters counters; ///< added per such sample, besides its primary ray
    };
    std::vector<MissAnswer> m_misses;
    std::vector<uint64_t> m_missSamples; ///< per policy: samples that took the miss answer untraced
    /// Where the camera's rays can meet the tracer's bounded primitives (Camera::rasterFootprint
    /// of Tracer::bounds()); none where every ray may (the box reaches behind the eye) or where
    /// the scene has planes, which any ray may meet.
    std::optional<Camera::RasterRect> m_footprint;
    RayCounters m_rays;
    uint64_t m_samples = 0;
    std::vector<PolicyCost> m_costs;
    std::vector<int64_t> m_nanoseconds;
    int m_runPolicy = -1;
    Clock::time_point m_runStart;
};

} // namespace mvcl::detail
