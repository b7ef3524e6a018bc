// Process-wide allocator settings for rendering.
#pragma once

namespace tandem {

// Frames allocate and free the same large temporaries every frame (filtered copies, mip chains,
// gradient images of several MB). glibc hands such blocks back to the system on free (mapped
// separately above its threshold, or trimmed off the heap's top), and the next frame faults
// every page back in zero-filled: on a VM a fault costs microseconds, and a 960x540 frame of the
// depth-of-field passes spent more time faulting than filtering. This keeps freed memory for
// reuse (blocks up to 32 MB, glibc's largest threshold, come from the heap; the heap is not
// trimmed). Call once at start-up, before threads; a no-op off glibc.
void keepFreedMemoryForReuse();

}  // namespace tandem
