#pragma once
// What the lens conformance checks (LensConformance.h) are built from, and what other lens
// tests share with them: random valid property values and regions, comparing policies and
// images, and rendering a policy map of builtin:cube-in-cube at a small size with one sample
// per pixel.

#include <mvcl/lens/LensStack.h>
#include <mvcl/lens/PolicyComposition.h>
#include <mvcl/model/BuiltinScenes.h>
#include <mvcl/tracer/Tracer.h>
#include <mvcl/view/Camera.h>
#include <mvcl/view/Renderer.h>

#include <gtest/gtest.h>

#include <functional>
#include <initializer_list>
#include <memory>
#include <random>
#include <string>

namespace mvcl::test {

using LensFactory = std::function<std::shared_ptr<Lens>()>;
using Random = std::mt19937;

inline constexpr int kConformanceWidth = 48;
inline constexpr int kConformanceHeight = 36;

// ---------------------------------------------------------------------------------------------
// Random valid values

/// A random value inside `decl`'s range; unbounded ranges, Int and Color are drawn from a
/// finite part of it.
PropertyValue randomValidValue(const PropertyDecl &decl, Random &random);

/// Stages random valid values for every property (including "rays") and commits.
void randomizeProperties(Lens &lens, Random &random);

/// A rectangle or ellipse that always covers the image centre, so any two of them overlap.
LensRegion randomCentralRegion(Random &random, float featherPixels = 0.f);

/// A lens made by `create` with random properties and region, committed.
std::shared_ptr<Lens> randomLens(const LensFactory &create, Random &random, float featherPixels = 0.f);

/// "type{name=value ...}" of the committed values, for failure messages.
std::string describeValues(const Lens &lens);

// ---------------------------------------------------------------------------------------------
// Comparing policies and images

/// Every field of `p` on one line, for failure messages.
std::string describePolicy(const PixelPolicy &p);

/// Every pixel blends the same policies with the same weights (table order may differ).
::testing::AssertionResult samePolicyMaps(const PolicyMap &a, const PolicyMap &b);

/// Images agree when no channel of any pixel differs by more than `tolerance` (linear light).
::testing::AssertionResult sameImages(const Framebuffer &a, const Framebuffer &b, float tolerance);

// ---------------------------------------------------------------------------------------------
// Rendering

/// builtin:cube-in-cube, its tracer and camera; built once, shared read-only by all threads.
struct ConformanceScene {
    Scene scene = makeBuiltinScene("cube-in-cube");
    Tracer tracer{scene};
    Camera camera = Camera::fromDesc(scene.cameras.front());
};

/// The one ConformanceScene, built on first use.
const ConformanceScene &conformanceScene();

/// `map` rendered over the conformance scene at the map's size, one sample per pixel, on
/// `threads` threads (0: the renderer's default).
Framebuffer renderMap(const PolicyMap &map, int threads = 0);

/// `stack` composed over the default RayPolicy and rendered with renderMap().
Framebuffer renderStack(const LensStack &stack, int width = kConformanceWidth,
                        int height = kConformanceHeight);

/// A stack of `lenses`, bottom first.
LensStack stackOf(std::initializer_list<std::shared_ptr<Lens>> lenses);

} // namespace mvcl::test
