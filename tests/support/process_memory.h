#pragma once
/// \file process_memory.h
/// \brief The test process's resident set, for the memory tests of the plan (issue 18).

#include <cstdint>

namespace osd_cull::test {

/// \brief Resident set size in KB (/proc/self/statm), 0 where there is none.
uint64_t residentKb();

}  // namespace osd_cull::test
