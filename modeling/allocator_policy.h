#pragma once
// Process-wide memory policy of the planesketch executable and the benchmarks.
//
// On the VMs this project runs on (CI, the benchmarks' machine), a page fault costs several
// microseconds: the kernel is paravirtualised, and each fault exits to the hypervisor. glibc's
// default policy hands every block over its (dynamic) mmap threshold, initially 128 KiB, back to
// the kernel when it is freed, and trims the top of the heap once 128 KiB are free there, so
// every operation that builds a large temporary (a sparse system, a union's copies, a mesh)
// faults all of its pages in again. In the deformation benchmark that was 16% of the process
// time (perf: exc_page_fault), and it made timings depend on the order of earlier allocations
// (bench/results/sculpt.md).
//
// keep_freed_memory() keeps freed memory in the process instead: blocks up to 32 MiB come from
// the heap (the dynamic threshold is switched off by setting it), and up to 1 GiB of free heap
// is kept untrimmed. The price is a resident size that stays at its peak, which for an
// interactive modeling tool is the right trade. The library never calls it: a process that
// embeds modeling/ keeps its own policy.
//
// PLANESKETCH_MALLOC=default in the environment leaves glibc's policy as it is (to measure the
// difference). Returns whether the policy was applied. No-op outside glibc.
namespace ps {

bool keep_freed_memory();

}  // namespace ps
