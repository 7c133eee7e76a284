#include "PixelTracer_p.h"

#include "BlockEstimateScale_p.h"

#include <mvcl/model/Scene.h>
#include <mvcl/tracer/Hit.h>
#include <mvcl/tracer/Tracer.h>

#include <algorithm>
#include <array>
#include <bit>
#include <climits>
#include <cmath>
#include <cstdint>

namespace mvcl::detail {

namespace {

/// 32-bit integer hash (lowbias32): per-pixel rotations without shared state.
uint32_t hash32(uint32_t x) {
    x ^= x >> 16;
    x *= 0x7feb352du;
    x ^= x >> 15;
    x *= 0x846ca68bu;
    x ^= x >> 16;
    return x;
}

double unitDouble(uint32_t bits) { return double(bits) * (1.0 / 4294967296.0); }

// R2: the inverse plastic number and its square (1/g, 1/g²), g³ = g + 1.
constexpr double kR2a = 0.75487766624669276005;
constexpr double kR2b = 0.56984029099805326591;

} // namespace

PixelSequence::PixelSequence(int x, int y, uint32_t seed) {
    const uint32_t key = hash32(uint32_t(y) * 0x9e3779b1u ^ uint32_t(x) ^ hash32(seed));
    m_u0 = 0.5 + unitDouble(key);
    m_v0 = 0.5 + unitDouble(hash32(key));
}

glm::vec2 PixelSequence::offset(uint32_t k) const {
    if (k == 0) return {0.5f, 0.5f};
    // One sequence for all samples, not two independently rotated halves: the halves would make
    // an even/odd error estimate exact in expectation, but cost 20–100 % more squared error at
    // the same sample count (measured, docs/benchmarks.md), which every image would pay.
    const double u = m_u0 + double(k) * kR2a;
    const double v = m_v0 + double(k) * kR2b;
    // Rounded to float once; the largest float below 1 keeps the sample inside the pixel.
    const float below1 = 0x1.fffffep-1f;
    return {std::min(float(u - std::floor(u)), below1), std::min(float(v - std::floor(v)), below1)};
}

glm::vec2 sampleOffset(int x, int y, uint32_t k, uint32_t seed) { return PixelSequence(x, y, seed).offset(k); }

namespace {

/// Per channel, the variance of the mean of a + b samples from the sums of two groups of them
/// (a and b samples), were the groups independent: (A − B)²·ab/(a + b)².
glm::vec3 varianceFromGroups(const glm::vec3 &sumA, float a, const glm::vec3 &sumB, float b) {
    const glm::vec3 d = sumA / a - sumB / b;
    return d * d * (a * b / ((a + b) * (a + b)));
}

} // namespace

glm::vec3 PixelSamples::blockVariance() const {
    // The first 2^m samples and the rest; at a power of two, its two halves.
    const uint32_t power = std::bit_floor(count);
    const bool halves = power == count;
    const glm::vec3 first = halves ? halfPrefixSum : prefixSum;
    const uint32_t a = halves ? power / 2 : power;
    return varianceFromGroups(first, float(a), sum - first, float(count - a)) *
           estimateScale(kBlockEstimateScale, count);
}

glm::vec3 PixelSamples::earlierBlockVariance() const {
    // The first p samples (p the last power of two below count) from their halves.
    const uint32_t power = std::bit_floor(count);
    const bool halves = power == count;
    const uint32_t p = halves ? power / 2 : power;
    const glm::vec3 whole = halves ? halfPrefixSum : prefixSum;
    const glm::vec3 half = halves ? quarterOrNextThreeQuarterSum : halfPrefixSum;
    return varianceFromGroups(half, float(p / 2), whole - half, float(p / 2)) *
           estimateScale(kEarlierEstimateScale, count);
}

glm::vec3 PixelSamples::laterBlockVariance() const {
    // The two halves of the second half of the first 2^m samples, 2^m = bit_floor(count).
    const uint32_t quarter = std::bit_floor(count) / 4;
    return varianceFromGroups(threeQuarterSum - halfPrefixSum, float(quarter), prefixSum - threeQuarterSum,
                              float(quarter)) *
           estimateScale(kLaterEstimateScale, count);
}

float PixelSamples::relativeError() const {
    if (count < 2) return INFINITY;
    const glm::vec3 all = sum / float(count);
    const glm::vec3 variance = count >= 4 ? glm::max(blockVariance(), earlierBlockVariance()) : blockVariance();
    const glm::vec3 sigma = glm::sqrt(variance);
    return (sigma.x + sigma.y + sigma.z) / std::sqrt(1e-4f + std::max(all.x + all.y + all.z, 0.f));
}

float PixelSamples::relativeMse(ImageEstimate source) const {
    if (count < 2) return 0.f;
    const glm::vec3 all = sum / float(count);
    glm::vec3 variance;
    if (count < 4) variance = blockVariance();
    else if (source == ImageEstimate::EveryPixelAlike) variance = (blockVariance() + laterBlockVariance()) * 0.5f;
    else variance = laterBlockVariance();
    const glm::vec3 relative = variance / (all * all + 0.01f);
    return (relative.x + relative.y + relative.z) / 3.f;
}

PixelTracer::PixelTracer(const WhittedIntegrator &integrator, const Camera &camera, const PolicyMap &map,
                         uint32_t seed, StageSelection stages)
    : m_integrator(integrator), m_camera(camera), m_map(map), m_seed(seed),
      m_costs(map.policies().size()), m_nanoseconds(map.policies().size(), 0), m_runStart(Clock::now()) {
    // Which stages each policy needs is decided here, once, not at every ray.
    m_plans.reserve(map.policies().size());
    m_misses.resize(map.policies().size());
    m_missSamples.assign(map.policies().size(), 0);
    for (const PixelPolicy &policy : map.policies()) {
        m_plans.push_back(integrator.plan(policy.ray, stages));
        MissAnswer &miss = m_misses[m_plans.size() - 1];
        miss.isPlain = integrator.plainMissRadiance(policy.ray, m_plans.back(), miss.radiance, miss.counters);
    }
    const Tracer &tracer = integrator.tracer();
    if (tracer.scene().planes.empty()) m_footprint = camera.rasterFootprint(tracer.bounds(), map.width(), map.height());
}

void PixelTracer::chargeRun(int policy) {
    // Time is charged per run of equal policy, so the clock is read only where the policy
    // changes (lens edges), not per pixel.
    if (policy == m_runPolicy) return;
    const Clock::time_point now = Clock::now();
    if (m_runPolicy >= 0)
        m_nanoseconds[size_t(m_runPolicy)] +=
            std::chrono::duration_cast<std::chrono::nanoseconds>(now - m_runStart).count();
    m_runStart = now;
    m_runPolicy = policy;
}

void PixelTracer::endRun() { chargeRun(-1); }

glm::vec3 PixelTracer::traceTerms(int x, int y, const glm::vec2 &position) {
    // Each term's rays and time are charged to its own policy.
    const int width = m_map.width(), height = m_map.height();
    glm::vec3 value(0.f);
    for (const PolicyTerm &term : m_map.terms(x, y)) {
        chargeRun(term.policy);
        const PixelPolicy &policy = m_map.policy(term.policy);
        const uint64_t raysBefore = m_rays.total();
        const glm::vec2 p = policy.samplePosition(position, width, height);
        value += term.weight * m_integrator.radiance(m_camera.generateRay(p.x, p.y, width, height), policy.ray,
                                                     m_plans[term.policy], m_rays);
        m_costs[term.policy].rays += m_rays.total() - raysBefore;
    }
    return value;
}

void PixelTracer::addSamples(int x, int y, uint32_t endSample, PixelSamples &samples) {
    if (samples.count >= endSample) return;
    const std::span<const PolicyTerm> terms = m_map.terms(x, y);
    const int width = m_map.width(), height = m_map.height();
    const glm::vec2 pixel{float(x), float(y)};
    const PixelSequence sequence(x, y, m_seed);
    if (terms.size() == 1) {
        const uint16_t index = terms[0].policy;
        chargeRun(index);
        const PixelPolicy &policy = m_map.policy(index);
        const IntegratorPlan &plan = m_plans[index];
        const uint64_t raysBefore = m_rays.total();
        for (uint32_t k = samples.count; k < endSample; ++k) {
            const glm::vec2 p = policy.samplePosition(pixel + sequence.offset(k), width, height);
            const glm::vec3 value =
                m_integrator.radiance(m_camera.generateRay(p.x, p.y, width, height), policy.ray, plan, m_rays);
            samples.add(k, value);
        }
        m_costs[index].rays += m_rays.total() - raysBefore;
        samples.rays += uint32_t(m_rays.total() - raysBefore);
        ++m_costs[index].pixels;
        m_samples += endSample - samples.count;
        samples.count = endSample;
        return;
    }
    // A feathered edge: each sample blends every term at the same position.
    const uint64_t raysBefore = m_rays.total();
    for (uint32_t k = samples.count; k < endSample; ++k) {
        const glm::vec3 value = traceTerms(x, y, pixel + sequence.offset(k));
        samples.add(k, value);
    }
    samples.rays += uint32_t(m_rays.total() - raysBefore);
    for (const PolicyTerm &term : terms) ++m_costs[term.policy].pixels;
    m_samples += uint64_t(endSample - samples.count) * terms.size();
    samples.count = endSample;
}

int PixelTracer::blockPolicy(int x0, int y0, int x1, int y1) const {
    // A map of one mix (no lens on the image) has it at every pixel.
    if (m_map.mixCount() == 1) {
        const std::span<const PolicyTerm> terms = m_map.mixTerms(0);
        return terms.size() == 1 ? int(terms[0].policy) : -1;
    }
    // Most blocks lie inside one region of the map: one mix for every pixel, compared row by row.
    const uint32_t mix = m_map.mixIndex(x0, y0);
    bool sameMix = true;
    for (int y = y0; y < y1; ++y) {
        const uint32_t *row = m_map.rowMixIndices(y).data();
        for (int x = x0; x < x1; ++x) sameMix &= row[x] == mix;
    }
    if (sameMix) {
        const std::span<const PolicyTerm> terms = m_map.mixTerms(mix);
        return terms.size() == 1 ? int(terms[0].policy) : -1;
    }
    // Different mixes may still be the one policy at weight 1.
    int shared = -1;
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
            const std::span<const PolicyTerm> terms = m_map.terms(x, y);
            if (terms.size() != 1 || (shared >= 0 && terms[0].policy != shared)) return -1;
            shared = terms[0].policy;
        }
    return shared;
}

void PixelTracer::addBlockSamples(int x0, int y0, int x1, int y1, const uint32_t *endSample,
                                  PixelSamples *samples, std::size_t rowStride) {
    const int side = x1 - x0, count = side * (y1 - y0);
    const int shared = count < 2 ? -1 : blockPolicy(x0, y0, x1, y1);
    if (shared >= 0 && count == Tracer::kPacketSize) {
        // The common block: all 16 pixels at the same count taking the same samples (every pass
        // of fixed or progressive sampling, and every full pass). Sample k of the block is one
        // packet, lane i pixel i, which is how the general loop below would fill it too.
        const uint32_t begin = samples->count, end = endSample[0];
        bool alike = true;
        for (int i = 0; i < count; ++i)
            alike &= samples[size_t(i / kBlockSide) * rowStride + size_t(i % kBlockSide)].count == begin &&
                     endSample[i] == end;
        if (alike && begin < end) {
            addUniformBlockSamples(x0, y0, begin, end, shared, samples, rowStride);
            return;
        }
    }
    // Pixel i of the block, row by row, and its sums (a table, not i / side and i % side: two
    // integer divisions per pixel and loop showed in the profile).
    std::array<int, kBlockSide * kBlockSide> xOf, yOf;
    std::array<PixelSamples *, kBlockSide * kBlockSide> sumsOf;
    for (int y = y0, i = 0; y < y1; ++y)
        for (int x = x0; x < x1; ++x, ++i) {
            xOf[size_t(i)] = x;
            yOf[size_t(i)] = y;
            sumsOf[size_t(i)] = samples + size_t(y - y0) * rowStride + size_t(x - x0);
        }
    if (shared < 0) {
        for (int i = 0; i < count; ++i) addSamples(xOf[size_t(i)], yOf[size_t(i)], endSample[i], *sumsOf[size_t(i)]);
        return;
    }
    const PixelPolicy &policy = m_map.policy(uint16_t(shared));
    const int width = m_map.width(), height = m_map.height();
    chargeRun(shared);
    uint64_t blockRays = 0;
    // Each pixel's samples [begin, end) of this call.
    std::array<uint32_t, kBlockSide * kBlockSide> begin;
    uint32_t first = UINT32_MAX, last = 0;
    for (int i = 0; i < count; ++i) {
        begin[size_t(i)] = sumsOf[size_t(i)]->count;
        if (begin[size_t(i)] < endSample[i]) {
            first = std::min(first, begin[size_t(i)]);
            last = std::max(last, endSample[i]);
        }
    }
    // Each pixel's sequence, hashed once per call; sample 0 (the centre) needs none.
    std::array<PixelSequence, kBlockSide * kBlockSide> sequenceOf;
    if (last > 1)
        for (int i = 0; i < count; ++i) sequenceOf[size_t(i)] = PixelSequence(xOf[size_t(i)], yOf[size_t(i)], m_seed);
    // Whether the policy shapes rays (a magnifier): asked once, not per sample (a 3 × 3 compare).
    const bool shaped = policy.isShaped();
    PacketLanes &l = m_lanes;
    int lanes = 0;
    // Sample by sample, and a packet filled across samples: a refinement pass where a few pixels
    // of the block take many samples still traces full packets (of rays through one pixel or two,
    // the most coherent there are). Each pixel's sums still add its samples in order k = count,
    // count + 1, …: its lanes come in that order, and packets are summed in the order traced.
    for (uint32_t k = first; k < last; ++k) {
        for (int i = 0; i < count; ++i) {
            if (k < begin[size_t(i)] || k >= endSample[i]) continue;
            const int x = xOf[size_t(i)], y = yOf[size_t(i)];
            const glm::vec2 position = glm::vec2{float(x), float(y)} + sequenceOf[size_t(i)].offset(k);
            l.positions[size_t(lanes)] = shaped ? policy.samplePosition(position, width, height) : position;
            l.sums[size_t(lanes)] = sumsOf[size_t(i)];
            l.sample[size_t(lanes++)] = k;
            if (lanes == Tracer::kPacketSize) {
                blockRays += traceLanes(lanes, shared);
                lanes = 0;
            }
        }
    }
    if (lanes > 0) blockRays += traceLanes(lanes, shared);
    m_costs[size_t(shared)].rays += blockRays;
    for (int i = 0; i < count; ++i) {
        // As addSamples(): a pixel counts once per call, and only if it took samples.
        if (begin[size_t(i)] >= endSample[i]) continue;
        ++m_costs[size_t(shared)].pixels;
        m_samples += endSample[i] - begin[size_t(i)];
        sumsOf[size_t(i)]->count = endSample[i];
    }
}

bool PixelTracer::blockMisses(int x0, int y0, int policy, bool shaped) const {
    // A magnifier's rays do not go through their pixels.
    if (!m_footprint || shaped || !m_misses[size_t(policy)].isPlain) return false;
    const Camera::RasterRect &r = *m_footprint;
    // The block's sample positions lie in [x0, x0 + side) × [y0, y0 + side).
    return float(x0 + kBlockSide) <= r.x0 || float(x0) >= r.x1 || float(y0 + kBlockSide) <= r.y0 || float(y0) >= r.y1;
}

void PixelTracer::addUniformBlockSamples(int x0, int y0, uint32_t begin, uint32_t end, int shared,
                                         PixelSamples *samples, std::size_t rowStride) {
    const PixelPolicy &policy = m_map.policy(uint16_t(shared));
    const int width = m_map.width(), height = m_map.height();
    chargeRun(shared);
    PacketLanes &l = m_lanes;
    constexpr int kLanes = Tracer::kPacketSize;
    const bool shaped = policy.isShaped();
    if (blockMisses(x0, y0, shared, shaped)) {
        // Every ray of the block misses: each sample is the policy's one miss value, with the
        // counts the traced rays would have added (a primary ray each), and no ray is made.
        const MissAnswer &miss = m_misses[size_t(shared)];
        for (int i = 0; i < kLanes; ++i) {
            PixelSamples &s = samples[size_t(i / kBlockSide) * rowStride + size_t(i % kBlockSide)];
            for (uint32_t k = begin; k < end; ++k) s.add(k, miss.radiance);
            s.rays += end - begin;
            s.count = end;
        }
        const uint64_t rays = uint64_t(end - begin) * kLanes;
        m_missSamples[size_t(shared)] += rays; // their counts are added up in rays()
        m_costs[size_t(shared)].rays += rays;
        m_costs[size_t(shared)].pixels += kLanes;
        m_samples += rays;
        return;
    }
    for (int i = 0; i < kLanes; ++i)
        l.sums[size_t(i)] = samples + size_t(i / kBlockSide) * rowStride + size_t(i % kBlockSide);
    std::array<glm::vec2, kLanes> pixelOf;
    for (int i = 0; i < kLanes; ++i) pixelOf[size_t(i)] = {float(x0 + i % kBlockSide), float(y0 + i / kBlockSide)};
    // Each pixel's sequence, hashed once per call; sample 0 (the centre) needs none.
    std::array<PixelSequence, kLanes> sequenceOf;
    if (end > 1)
        for (int i = 0; i < kLanes; ++i) sequenceOf[size_t(i)] = PixelSequence(x0 + i % kBlockSide, y0 + i / kBlockSide, m_seed);
    uint64_t blockRays = 0;
    for (uint32_t k = begin; k < end; ++k) {
        for (int i = 0; i < kLanes; ++i) {
            const glm::vec2 position = pixelOf[size_t(i)] + sequenceOf[size_t(i)].offset(k);
            l.positions[size_t(i)] = shaped ? policy.samplePosition(position, width, height) : position;
            l.sample[size_t(i)] = k;
        }
        blockRays += traceLanes(kLanes, shared);
    }
    m_costs[size_t(shared)].rays += blockRays;
    m_costs[size_t(shared)].pixels += kLanes;
    m_samples += uint64_t(end - begin) * kLanes;
    for (int i = 0; i < kLanes; ++i) l.sums[size_t(i)]->count = end;
}

uint64_t PixelTracer::traceLanes(int lanes, int shared) {
    const PixelPolicy &policy = m_map.policy(uint16_t(shared));
    PacketLanes &l = m_lanes;
    const size_t n = size_t(lanes);
    m_camera.generateRays({l.positions.data(), n}, m_map.width(), m_map.height(), {l.rays.data(), n});
    const uint32_t found =
        m_integrator.tracer().closestHits({l.rays.data(), n}, policy.ray.query(RayType::Primary), {l.hits.data(), n});
    m_integrator.radianceFromHits({l.rays.data(), n}, {l.hits.data(), n}, found, policy.ray, m_plans[size_t(shared)],
                                  {l.counters.data(), n}, {l.values.data(), n});
    uint64_t rays = 0;
    for (size_t j = 0; j < n; ++j) {
        PixelSamples &s = *l.sums[j];
        s.add(l.sample[j], l.values[j]);
        const uint64_t total = l.counters[j].total(), sampleRays = total - l.totals[j];
        l.totals[j] = total;
        s.rays += uint32_t(sampleRays);
        rays += sampleRays;
    }
    return rays;
}

glm::vec3 PixelTracer::sampleAt(int x, int y, const glm::vec2 &position) {
    m_samples += m_map.terms(x, y).size();
    return traceTerms(x, y, position);
}

RayCounters PixelTracer::rays() const {
    RayCounters all = m_rays;
    for (const RayCounters &lane : m_lanes.counters) all += lane;
    // The untraced misses: a primary ray each, and their policy's miss counts n times over
    // (by doubling: RayCounters has no product, and a field added to it later is summed too).
    for (size_t policy = 0; policy < m_missSamples.size(); ++policy) {
        uint64_t n = m_missSamples[policy];
        all.primary += n;
        for (RayCounters power = m_misses[policy].counters; n; n >>= 1) {
            if (n & 1u) all += power;
            power += power;
        }
    }
    return all;
}

void PixelTracer::addCostsTo(std::vector<PolicyCost> &costs) const {
    costs.resize(m_costs.size());
    for (size_t i = 0; i < m_costs.size(); ++i) {
        costs[i].pixels += m_costs[i].pixels;
        costs[i].rays += m_costs[i].rays;
        costs[i].milliseconds += double(m_nanoseconds[i]) * 1e-6;
    }
}

} // namespace mvcl::detail
