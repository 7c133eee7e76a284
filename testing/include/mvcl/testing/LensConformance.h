#pragma once
/// \file LensConformance.h
/// The lens conformance checks (the composition rules of docs/architecture.md), part of
/// mvcl::testing. Each check takes a factory for the lens under test and returns an
/// AssertionResult, so the same checks run over every lens type of a plugin
/// (mvcl-lens-conformance, LensConformanceSuite.h) and over deliberately broken test lenses
/// that prove every check can fail.
///
/// Images are rendered from builtin:cube-in-cube at a small size with one sample per pixel:
/// algebra claims are checked by rendering permutations, not by trusting the composition code
/// that the claims are about. What the checks are built from is in LensConformanceSupport.h.

#include <mvcl/testing/LensConformanceSupport.h>

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace mvcl::test {

/// A lens type as the checks see it: a name for messages and a way to make one.
struct LensSubject {
    std::string name;
    LensFactory create;
};

/// Colour maps multiply in a different order when lenses swap, so commuting colour lenses
/// agree only up to rounding.
inline constexpr float kAlgebraTolerance = 1e-5f;

/// (a) create() gives a committed, enabled lens on valid defaults that reads all its parameters.
::testing::AssertionResult checkDefaults(const std::string &typeName, const LensFactory &create);

/// (b) every property survives setPropertyText(value.toString()) and commits.
::testing::AssertionResult checkPropertyRoundTrip(const LensFactory &create, Random &random);

/// (c) bad values, bad texts and unknown keys throw mvcl::Error naming the lens and the key,
/// and leave both the staged value and the committed snapshot as they were.
::testing::AssertionResult checkRejectsBadValues(const LensFactory &create);

/// (d) a disabled lens, anywhere in the stack, changes neither the policy map nor the image.
::testing::AssertionResult checkDisabledChangesNothing(const LensFactory &create, Random &random);

/// (e) a lens whose region lies wholly outside the image changes nothing.
::testing::AssertionResult checkOutsideImageChangesNothing(const LensFactory &create,
                                                           Random &random);

/// (f1) a lens declared idempotent renders the same stacked twice as once: over the same
/// region everywhere, over two overlapping regions wherever both cover the pixel fully.
::testing::AssertionResult checkIdempotence(const LensFactory &create, Random &random);

/// (f2) a lens declared commutative renders the same when swapped with every other lens that
/// declares it too (and with itself on other properties), over overlapping, partly feathered
/// regions.
::testing::AssertionResult checkCommutes(const LensSubject &subject,
                                         const std::vector<LensSubject> &others, Random &random);

/// (g) the "rays" mask: ray types outside it keep no visibility, shading switches or ray
/// shaping from the lens, types inside keep exactly what the full mask gives, and the colour
/// stage (per pixel) always stays. With rays=none a lens without a colour stage changes nothing.
::testing::AssertionResult checkRayTypeMask(const LensFactory &create, Random &random);

/// (h) one thread commits random changes (at least `commits`) while two compose (one also
/// renders) from snapshots: nothing crashes, versions never go back, and every composed policy
/// is the composition of one committed snapshot, never a mix of two.
::testing::AssertionResult checkThreadSafety(const LensFactory &create, Random &random,
                                             int commits = 200);

/// (i) the property table documents itself: a description, a doc sentence per property,
/// unique lowerCamelCase names, defaults inside declared ranges, Int/Real bounded below; a
/// spaceFrom or usedWhen names a Choice of the lens and only values it offers, and spaceFrom
/// maps every choice (the declared space being the default choice's).
::testing::AssertionResult checkDocumented(const LensFactory &create);

/// (j) the context: a lens that does not declare LensInfo::dependsOnView contributes the same
/// under another camera and image size; for every lens, snapshotIn() of the committed context
/// is snapshot() itself, and snapshotIn() of another context is what a commit there gives (and
/// the same pointer when asked twice).
::testing::AssertionResult checkContext(const LensFactory &create, Random &random);

} // namespace mvcl::test
