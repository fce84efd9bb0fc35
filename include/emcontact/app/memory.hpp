#pragma once
// The C library's allocator for a long implicit run: freed memory is kept for the next
// allocation of the same size instead of being returned to the system and faulted in again.

namespace emc::app {

/// With glibc, and unless GLIBC_TUNABLES is set (the user's own malloc settings win): no
/// allocation is served by its own mmap, and the heap's free top is never trimmed. Every Newton
/// iterate allocates and frees the same vectors and matrices; glibc would map the large ones
/// afresh (zeroed pages, one fault per page) and trim the heap after each free. Returns whether
/// the settings were made. Call before anything allocates much (before MPI starts).
bool keep_freed_memory();

}  // namespace emc::app
