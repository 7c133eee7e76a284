#!/usr/bin/python3
"""Writes framework/src/view/{Block,Earlier,Later}EstimateScaleTable.cpp: for each sample count n, the factor
that turns a pixel's two-block variance estimate (PixelSamples) into the expected squared error
of its mean, E[e²] / E[v], for the pixels whose error dominates an image: pixels crossed by an
edge.

Why a table: a pixel's samples are consecutive points of one R2 sequence (rotated per pixel),
so the error of their mean is not that of independent samples. The two blocks (the first 2^m
samples and the rest) cancel each other's error in the mean by an amount that depends on n
only: at 64 samples the whole prefix is spread especially well and the blocks' difference
overstates the error about 2.7×; just past a power of two the second block has a few samples
and overstates it up to 70×. The images measured against converged references (mvcl-bench
convergence, docs/benchmarks.md) over-estimate by the same factors as this model does.

The model: a pixel is the unit square, crossed by a straight edge (value 1 on one side, 0 on
the other) through a uniformly random point of the square at a uniformly random angle; the
pixel's rotation of the sequence is uniformly random, sample 0 is the pixel's centre, as in
PixelSequence. The exact covered area is the true value; e is the mean of the first n samples
minus it; v is PixelSamples' two-block variance of that mean. Both are averaged over --edges
random edges (the same edges for every n, so neighbouring entries are smooth).

    scripts/block-estimate-scale.py                     # the committed tables: ~3 min, 1 core
    scripts/block-estimate-scale.py --edges 20000 -o /tmp     # a quick look

Needs Debian's python3-numpy, hence /usr/bin/python3.
"""
import argparse
import os
import sys

import numpy as np

# R2: the inverse plastic number and its square, as in PixelTracer.cpp.
R2A = 0.75487766624669276005
R2B = 0.56984029099805326591


def covered_area(nx, ny, c):
    """Area of {p in [0,1]²: nx·p.x + ny·p.y < c}: the distribution function of the sum of two
    uniform variables on [0, |nx|] and [0, |ny|], shifted for negative components."""
    t = c - np.minimum(nx, 0.0) - np.minimum(ny, 0.0)
    b1 = np.abs(nx) + 1e-300
    b2 = np.abs(ny) + 1e-300
    ramp = lambda s: np.maximum(s, 0.0) ** 2  # noqa: E731
    return np.clip((ramp(t) - ramp(t - b1) - ramp(t - b2) + ramp(t - b1 - b2)) / (2.0 * b1 * b2), 0.0, 1.0)


def block_sizes(counts):
    """The first block of PixelSamples: the largest power of two below n (n/2 at a power of two)."""
    power = 2 ** np.floor(np.log2(counts)).astype(np.int64)
    return np.where(power == counts, counts // 2, power)


def sums_over_edges(max_count, edges, seed):
    """Σ v, Σ w, Σ g and Σ e² over the edges, for n = 0 … max_count (0 below n = 2; w and g below
    n = 4): v from the two blocks, w from the halves of the first block (the earlier look), g from
    the halves of the second half of the first 2^m samples, 2^m the largest power of two not above
    n (the later look)."""
    rng = np.random.default_rng(seed)
    k = np.arange(max_count, dtype=np.float64)
    counts = np.arange(2, max_count + 1)
    first = block_sizes(counts)
    half = np.maximum(first // 2, 1)  # the earlier look's halves (n ≥ 4: first ≥ 2)
    power = 2 ** np.floor(np.log2(counts)).astype(np.int64)
    later = np.maximum(power // 4, 1)  # the later look's halves: [2^m/2, 3·2^m/4) and the rest of 2^m
    sum_v = np.zeros(max_count + 1)
    sum_w = np.zeros(max_count + 1)
    sum_g = np.zeros(max_count + 1)
    sum_e2 = np.zeros(max_count + 1)
    chunk = max(1, 4_000_000 // max_count)
    done = 0
    while done < edges:
        m = min(chunk, edges - done)
        done += m
        angle = rng.uniform(0.0, 2.0 * np.pi, m)
        nx, ny = np.cos(angle), np.sin(angle)
        through = rng.uniform(0.0, 1.0, (m, 2))
        c = nx * through[:, 0] + ny * through[:, 1]
        u0 = 0.5 + rng.uniform(0.0, 1.0, m)
        v0 = 0.5 + rng.uniform(0.0, 1.0, m)
        u = np.mod(u0[:, None] + k[None, :] * R2A, 1.0)
        v = np.mod(v0[:, None] + k[None, :] * R2B, 1.0)
        u[:, 0] = 0.5
        v[:, 0] = 0.5
        inside = (nx[:, None] * u + ny[:, None] * v < c[:, None]).astype(np.float64)
        prefix = np.cumsum(inside, axis=1)  # prefix[:, n - 1]: the sum of the first n samples
        total = prefix[:, counts - 1]
        block = prefix[:, first - 1]
        d = block / first - (total - block) / (counts - first)
        sum_v[2:] += (d * d * (first * (counts - first)) / (counts * counts)).sum(axis=0)
        early = prefix[:, half - 1]
        d = early / half - (block - early) / half
        sum_w[4:] += (d * d / 4.0).sum(axis=0)[2:]
        at_half, at_three_quarters, at_power = prefix[:, 2 * later - 1], prefix[:, 3 * later - 1], prefix[:, power - 1]
        d = (at_three_quarters - at_half) / later - (at_power - at_three_quarters) / later
        sum_g[4:] += (d * d / 4.0).sum(axis=0)[2:]
        error = total / counts - covered_area(nx, ny, c)[:, None]
        sum_e2[2:] += (error * error).sum(axis=0)
    return sum_v, sum_w, sum_g, sum_e2


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--max-count", type=int, default=4096, help="largest n in the table (a power of two)")
    parser.add_argument("--edges", type=int, default=250_000, help="random edges averaged over")
    parser.add_argument("--seed", type=int, default=1)
    parser.add_argument("-o", "--output-dir", default="framework/src/view",
                        help="where the three tables go (<Name>EstimateScaleTable.cpp)")
    args = parser.parse_args()
    if args.max_count < 4 or args.max_count & (args.max_count - 1):
        sys.exit("block-estimate-scale: --max-count must be a power of two ≥ 4")

    sum_v, sum_w, sum_g, sum_e2 = sums_over_edges(args.max_count, args.edges, args.seed)
    block = np.ones(args.max_count + 1)
    block[2:] = sum_e2[2:] / sum_v[2:]
    earlier = np.ones(args.max_count + 1)
    earlier[4:] = sum_e2[4:] / sum_w[4:]
    later = np.ones(args.max_count + 1)
    later[4:] = sum_e2[4:] / sum_g[4:]

    looks = [("kBlockEstimateScale", block, "its two blocks (n ≥ 2)"),
             ("kEarlierEstimateScale", earlier, "the earlier look (n ≥ 4)"),
             ("kLaterEstimateScale", later, "the later look (n ≥ 4)")]
    for name, values, what in looks:
        text = ["%#.4gf" % value for value in values]
        rows = ["    " + ", ".join(text[i:i + 10]) for i in range(0, len(text), 10)]
        path = os.path.join(args.output_dir, name[1:] + "Table.cpp")
        with open(path, "w") as out:
            out.write("// Generated by scripts/block-estimate-scale.py --max-count %d --edges %d --seed %d;\n"
                      "// do not edit. For a pixel crossed by an edge, the squared error of the mean of n\n"
                      "// samples over PixelSamples' estimate of it from %s; 1 below.\n\n"
                      % (args.max_count, args.edges, args.seed, what))
            out.write('#include "BlockEstimateScale_p.h"\n\nnamespace mvcl::detail {\n\n')
            out.write("const std::array<float, kBlockEstimateScaleCounts + 1> %s = {\n%s,\n};\n"
                      % (name, ",\n".join(rows)))
            out.write("\n} // namespace mvcl::detail\n")
    print("wrote %s/*EstimateScaleTable.cpp: n = 2 … %d, blocks × %.3f … %.3f, earlier look × %.3f … %.3f, later look × %.3f … %.3f"
          % (args.output_dir, args.max_count, block[2:].min(), block[2:].max(), earlier[4:].min(), earlier[4:].max(),
             later[4:].min(), later[4:].max()))

if __name__ == "__main__":
    main()
