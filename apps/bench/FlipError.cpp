// LDR-FLIP after Andersson et al. 2020, "FLIP: A Difference Evaluator for Alternating Images".
// The constants are the paper's; where the paper leaves a choice open (filter support, borders)
// this follows what its authors chose: every filter is evaluated out to three standard
// deviations of its widest Gaussian, and borders replicate the edge pixel.

#include "FlipError.h"

#include <mvcl/core/Error.h>
#include <mvcl/core/WorkerPool.h>

#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

namespace mvcl::bench {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kQc = 0.7;   // exponent of the colour difference
constexpr double kQf = 0.5;   // exponent of the feature difference
constexpr double kPc = 0.4;   // fraction of the maximum colour distance ...
constexpr double kPt = 0.95;  // ... that maps to this fraction of the error range
constexpr double kFeatureWidthDegrees = 0.082; // peak-to-trough of the edge detector (2σ)

/// Linear sRGB → CIE XYZ (D65), the exact fractions of the sRGB definition, row by row.
constexpr double kRgbToXyzRows[3][3] = {
    {10135552.0 / 24577794.0, 8788810.0 / 24577794.0, 4435075.0 / 24577794.0},
    {2613072.0 / 12288897.0, 8788810.0 / 12288897.0, 887015.0 / 12288897.0},
    {1425312.0 / 73733382.0, 8788810.0 / 73733382.0, 70074185.0 / 73733382.0}};

struct ColourSpaces {
    glm::dmat3 rgbToXyz;
    glm::dmat3 xyzToRgb;
    glm::dvec3 white; // XYZ of linear RGB (1, 1, 1): the reference white of YCxCz and L*a*b*
    ColourSpaces() {
        for (int row = 0; row < 3; ++row)
            for (int column = 0; column < 3; ++column) rgbToXyz[column][row] = kRgbToXyzRows[row][column];
        xyzToRgb = glm::inverse(rgbToXyz);
        white = rgbToXyz * glm::dvec3(1.0);
    }
};

const ColourSpaces &colourSpaces() {
    static const ColourSpaces spaces;
    return spaces;
}

/// Linear RGB → YCxCz, the linearised (opponent) form of L*a*b*.
glm::dvec3 rgbToYcxcz(const glm::dvec3 &rgb) {
    const glm::dvec3 n = colourSpaces().rgbToXyz * rgb / colourSpaces().white;
    return {116.0 * n.y - 16.0, 500.0 * (n.x - n.y), 200.0 * (n.y - n.z)};
}

glm::dvec3 ycxczToRgb(const glm::dvec3 &ycxcz) {
    const double y = (ycxcz.x + 16.0) / 116.0;
    const glm::dvec3 n(y + ycxcz.y / 500.0, y, y - ycxcz.z / 200.0);
    return colourSpaces().xyzToRgb * (n * colourSpaces().white);
}

/// Linear RGB → CIE L*a*b*, then the Hunt adjustment (chroma scaled by 0.01 L*: dark colours
/// look less colourful).
glm::dvec3 rgbToHuntLab(const glm::dvec3 &rgb) {
    constexpr double delta = 6.0 / 29.0;
    const glm::dvec3 n = colourSpaces().rgbToXyz * rgb / colourSpaces().white;
    auto f = [](double t) { return t > delta * delta * delta ? std::cbrt(t) : t / (3.0 * delta * delta) + 4.0 / 29.0; };
    const double fx = f(n.x), fy = f(n.y), fz = f(n.z);
    const double lightness = 116.0 * fy - 16.0;
    return {lightness, 0.01 * lightness * 500.0 * (fx - fy), 0.01 * lightness * 200.0 * (fy - fz)};
}

/// HyAB: city-block in lightness, Euclidean in the chroma plane (better for large differences).
double hyab(const glm::dvec3 &a, const glm::dvec3 &b) {
    return std::fabs(a.x - b.x) + std::hypot(a.y - b.y, a.z - b.z);
}

using Kernel = std::vector<double>; // taps −r … r

/// Correlates `image` (w × h) with kx along rows and ky along columns, replicating the border.
/// A 2-D Gaussian (and each FLIP filter term) is such a product, so this equals the 2-D filter.
/// Rows are copied into a padded buffer and columns are summed row by row, so the inner loops
/// have no border tests (the bench evaluates thousands of images).
std::vector<float> filterSeparable(const std::vector<float> &image, int w, int h, const Kernel &kx, const Kernel &ky) {
    const int rx = int(kx.size() / 2), ry = int(ky.size() / 2);
    const std::vector<float> fx(kx.begin(), kx.end()), fy(ky.begin(), ky.end());
    std::vector<float> rows(image.size()), out(image.size());
    parallelForChunks(std::size_t(h), 0, 16, [&](std::size_t begin, std::size_t end) {
        std::vector<float> padded(std::size_t(w + 2 * rx));
        for (std::size_t y = begin; y < end; ++y) {
            const float *row = &image[y * std::size_t(w)];
            for (int x = -rx; x < w + rx; ++x) padded[std::size_t(x + rx)] = row[std::clamp(x, 0, w - 1)];
            float *target = &rows[y * std::size_t(w)];
            for (int x = 0; x < w; ++x) {
                float sum = 0.f;
                for (std::size_t i = 0; i < fx.size(); ++i) sum += fx[i] * padded[std::size_t(x) + i];
                target[x] = sum;
            }
        }
    });
    parallelForChunks(std::size_t(h), 0, 16, [&](std::size_t begin, std::size_t end) {
        for (std::size_t y = begin; y < end; ++y) {
            float *target = &out[y * std::size_t(w)];
            std::fill(target, target + w, 0.f);
            for (int j = -ry; j <= ry; ++j) {
                const float *source = &rows[std::size_t(std::clamp(int(y) + j, 0, h - 1)) * std::size_t(w)];
                const float weight = fy[std::size_t(j + ry)];
                for (int x = 0; x < w; ++x) target[x] += weight * source[x];
            }
        }
    });
    return out;
}

/// One Gaussian of a contrast sensitivity function in the spatial domain:
/// a·√(π/b)·exp(−π²·r²/b), r in degrees.
struct CsfTerm {
    double a, b;
};

/// Filters one YCxCz channel with the sum of its CSF terms, normalised to unit sum over the
/// (2r+1)² support. Each term is separable; the normalisation divides the 2-D sum of all terms.
std::vector<float> filterCsf(const std::vector<float> &channel, int w, int h, const std::vector<CsfTerm> &terms,
                             double ppd, int radius) {
    std::vector<Kernel> kernels;
    std::vector<double> weights;
    double total = 0.0;
    for (const CsfTerm &term : terms) {
        Kernel k(std::size_t(2 * radius + 1));
        for (int i = -radius; i <= radius; ++i) {
            const double degrees = double(i) / ppd;
            k[std::size_t(i + radius)] = std::exp(-kPi * kPi * degrees * degrees / term.b);
        }
        const double sum1d = std::accumulate(k.begin(), k.end(), 0.0);
        weights.push_back(term.a * std::sqrt(kPi / term.b));
        total += weights.back() * sum1d * sum1d;
        kernels.push_back(std::move(k));
    }
    std::vector<float> out(channel.size(), 0.f);
    for (std::size_t t = 0; t < kernels.size(); ++t) {
        const std::vector<float> filtered = filterSeparable(channel, w, h, kernels[t], kernels[t]);
        const double scale = weights[t] / total;
        for (std::size_t i = 0; i < out.size(); ++i) out[i] += float(scale * filtered[i]);
    }
    return out;
}

/// The 1-D factors of the edge (first derivative) or point (second derivative) detector.
/// `along` carries the derivative; its positive taps are scaled to sum to 1 and its negative
/// ones to −1 (the paper's normalisation of the 2-D filter, which factors because the Gaussian
/// across is positive); `across` is the Gaussian, unit sum.
void featureKernels(double ppd, bool points, Kernel &along, Kernel &across) {
    const double sd = 0.5 * kFeatureWidthDegrees * ppd;
    const int radius = int(std::ceil(3.0 * sd));
    along.assign(std::size_t(2 * radius + 1), 0.0);
    across.assign(along.size(), 0.0);
    for (int i = -radius; i <= radius; ++i) {
        const double g = std::exp(-double(i * i) / (2.0 * sd * sd));
        across[std::size_t(i + radius)] = g;
        along[std::size_t(i + radius)] = points ? (double(i * i) / (sd * sd) - 1.0) * g : -double(i) * g;
    }
    const double acrossSum = std::accumulate(across.begin(), across.end(), 0.0);
    for (double &v : across) v /= acrossSum;
    double positive = 0.0, negative = 0.0;
    for (double v : along) (v > 0.0 ? positive : negative) += v;
    for (double &v : along) v = v > 0.0 ? v / positive : v / -negative;
}

/// Magnitude of the detector's response in x and y at every pixel.
std::vector<float> featureMagnitude(const std::vector<float> &luminance, int w, int h, double ppd, bool points) {
    Kernel along, across;
    featureKernels(ppd, points, along, across);
    const std::vector<float> dx = filterSeparable(luminance, w, h, along, across);
    const std::vector<float> dy = filterSeparable(luminance, w, h, across, along);
    std::vector<float> magnitude(luminance.size());
    for (std::size_t i = 0; i < magnitude.size(); ++i) magnitude[i] = std::hypot(dx[i], dy[i]);
    return magnitude;
}

} // namespace

FlipReference::FlipReference(const Framebuffer &reference, double pixelsPerDegree)
    : m_width(reference.width()), m_height(reference.height()), m_pixelsPerDegree(pixelsPerDegree),
      m_reference(prepare(reference)) {}

FlipReference::Prepared FlipReference::prepare(const Framebuffer &image) const {
    const int w = image.width(), h = image.height();
    const std::size_t n = image.pixels().size();
    std::vector<float> opponent[3];
    for (auto &channel : opponent) channel.resize(n);
    std::vector<float> luminance(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 rgb = glm::clamp(glm::dvec3(image.pixels()[i]), 0.0, 1.0);
        const glm::dvec3 ycxcz = rgbToYcxcz(rgb);
        for (int c = 0; c < 3; ++c) opponent[c][i] = float(ycxcz[c]);
        luminance[i] = float((ycxcz.x + 16.0) / 116.0); // Y / Y_white, in [0, 1]
    }

    // Colour pipeline: CSF per opponent channel (achromatic, red-green, blue-yellow), all on
    // the support of the widest Gaussian (b = 0.04), as the paper's filters share one size.
    const double ppd = m_pixelsPerDegree;
    const int radius = int(std::ceil(3.0 * std::sqrt(0.04 / (2.0 * kPi * kPi)) * ppd));
    const std::vector<CsfTerm> csf[3] = {{{1.0, 0.0047}}, {{1.0, 0.0053}}, {{34.1, 0.04}, {13.5, 0.025}}};
    std::vector<float> filtered[3];
    for (int c = 0; c < 3; ++c) filtered[c] = filterCsf(opponent[c], w, h, csf[c], ppd, radius);

    Prepared prepared;
    for (auto &channel : prepared.lab) channel.resize(n);
    for (std::size_t i = 0; i < n; ++i) {
        const glm::dvec3 ycxcz(filtered[0][i], filtered[1][i], filtered[2][i]);
        // Filtering can leave the RGB cube; the paper clamps back into it before L*a*b*.
        const glm::dvec3 lab = rgbToHuntLab(glm::clamp(ycxczToRgb(ycxcz), 0.0, 1.0));
        for (int c = 0; c < 3; ++c) prepared.lab[c][i] = float(lab[c]);
    }
    // Feature pipeline on the unfiltered luminance.
    prepared.edges = featureMagnitude(luminance, w, h, ppd, false);
    prepared.points = featureMagnitude(luminance, w, h, ppd, true);
    return prepared;
}

std::vector<float> FlipReference::errorMap(const Framebuffer &test) const {
    if (test.width() != m_width || test.height() != m_height)
        throw Error("FLIP", "test image is " + std::to_string(test.width()) + "x" + std::to_string(test.height()) +
                                ", reference " + std::to_string(m_width) + "x" + std::to_string(m_height));
    const Prepared t = prepare(test);
    const Prepared &r = m_reference;
    // The largest colour distance: Hunt-adjusted green against blue.
    const double cmax = std::pow(hyab(rgbToHuntLab({0.0, 1.0, 0.0}), rgbToHuntLab({0.0, 0.0, 1.0})), kQc);
    const double knee = kPc * cmax;
    std::vector<float> error(t.edges.size());
    for (std::size_t i = 0; i < error.size(); ++i) {
        const double distance = std::pow(hyab({r.lab[0][i], r.lab[1][i], r.lab[2][i]},
                                               {t.lab[0][i], t.lab[1][i], t.lab[2][i]}),
                                          kQc);
        // Small differences spread over [0, p_t], the rest compressed into [p_t, 1].
        const double colour = distance < knee ? kPt / knee * distance
                                              : kPt + (distance - knee) / (cmax - knee) * (1.0 - kPt);
        const double edges = std::fabs(double(r.edges[i]) - t.edges[i]);
        const double points = std::fabs(double(r.points[i]) - t.points[i]);
        const double feature = std::pow(std::max(edges, points) / std::numbers::sqrt2, kQf);
        error[i] = float(std::pow(colour, 1.0 - feature));
    }
    return error;
}

double FlipReference::meanError(const Framebuffer &test) const {
    const std::vector<float> map = errorMap(test);
    double sum = 0.0;
    for (float v : map) sum += v;
    return map.empty() ? 0.0 : sum / double(map.size());
}

double flipError(const Framebuffer &test, const Framebuffer &reference, double pixelsPerDegree) {
    return FlipReference(reference, pixelsPerDegree).meanError(test);
}

} // namespace mvcl::bench
