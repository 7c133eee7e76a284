#include "core/HugePageAllocator_p.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

using mvcl::detail::HugePageAllocator;

TEST(HugePageAllocator, LargeAndSmallBuffersHoldWhatIsWrittenAndStartZeroed) {
    // Below and above the 1 MiB from which buffers get huge pages, at and above one huge page
    // (2 MiB of floats is 524,288), and one that is not a multiple of it: each is
    // value-initialised, written through and read back.
    for (std::size_t n : {std::size_t(1000), std::size_t(300'000), std::size_t(524'288), std::size_t(524'289),
                          std::size_t(3'000'001)}) {
        std::vector<float, HugePageAllocator<float>> v(n);
        ASSERT_EQ(v.size(), n);
        EXPECT_EQ(v.front(), 0.f);
        EXPECT_EQ(v.back(), 0.f);
        for (std::size_t i = 0; i < n; i += 4099) v[i] = float(i);
        v.back() = -1.f;
        for (std::size_t i = 0; i + 1 < n; i += 4099) EXPECT_EQ(v[i], float(i)) << "buffer of " << n;
        EXPECT_EQ(v.back(), -1.f);
#if defined(__linux__)
        // Large buffers start on a huge page, so that the kernel can back them with huge pages.
        if (n * sizeof(float) >= (std::size_t(1) << 20)) {
            EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % (std::uintptr_t(2) << 20), 0u);
        }
#endif
    }
}

TEST(HugePageAllocator, BuffersGrowAndShrinkAcrossTheThreshold) {
    std::vector<double, HugePageAllocator<double>> v(10, 1.5);
    v.resize(400'000, 2.5); // 3.2 MB: moves into a large buffer
    EXPECT_EQ(v[9], 1.5);
    EXPECT_EQ(v[399'999], 2.5);
    v.assign(7, 3.5);
    v.shrink_to_fit(); // back below the threshold
    EXPECT_EQ(v.size(), 7u);
    EXPECT_EQ(v[6], 3.5);
}
