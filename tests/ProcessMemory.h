#pragma once
// The memory this test process has used, for tests that check that a refused file was not read.

#include <sys/resource.h>

namespace mvcl::test {

/// Peak resident memory of this process so far, in MiB.
inline long peakResidentMiB() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024;
}

} // namespace mvcl::test
