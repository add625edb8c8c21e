#pragma once
// Heap allocations of this process so far (see allocation_counter.cpp).
long heap_allocations();
