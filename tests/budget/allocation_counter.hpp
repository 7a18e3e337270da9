// Counts heap allocations made by this process while armed. The test binary that links
// allocation_counter.cpp replaces malloc/calloc/realloc/free and every operator new/delete.
#pragma once

#include <cstddef>

namespace dpcr::test {

void ArmAllocationCounter();
// Disarms and returns the number of allocations (malloc, calloc, realloc, new) while armed.
std::size_t DisarmAllocationCounter();

}  // namespace dpcr::test
