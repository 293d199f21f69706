// The bytes this test program holds through operator new, and their peak: a measure of
// what code keeps that, unlike resident memory, the operating system does not decide
// (page sizes, what it leaves resident, a sanitizer's quarantine). heap_peak.cpp replaces
// the global operator new and delete of the test program (of no library or program).
#pragma once

#include <cstddef>

namespace meander::test {

// Starts a new peak from the bytes live now, and returns them.
size_t reset_heap_peak();
// The most bytes live at once since reset_heap_peak().
size_t heap_peak();

} // namespace meander::test
