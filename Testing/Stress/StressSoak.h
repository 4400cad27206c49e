/**
 * Soak of the caustics passes (CausticsStress --soak F): F frames per technique of
 * the ball lens with the window resized every frame (four sizes) and three actors
 * added and removed (a glass sphere made anew each time it comes back, a diffuse
 * box, a mirror), a cycle of 16 frames. GPU objects and bytes (the passes'
 * bookkeeping, vtkCausticsRenderPass::GetGraphicsMemory()) and the process's
 * resident memory (/proc/self/statm) are sampled after every frame; after a warm-up
 * of a quarter of the frames (at least one cycle) they must stay flat:
 * - no frame of the last half holds more GPU objects or bytes than the peak of the
 *   first quarter;
 * - the peak RSS of the last half exceeds the peak of the first quarter by less
 *   than MemoryGrowthBound, and so does the heap in use (glibc's mallinfo2: what
 *   the process allocated and has not freed, llvmpipe's textures included);
 * - the bookkeeping counted objects while rendering, and after
 *   ReleaseGraphicsResources() it holds no object and no byte;
 * - a technique that makes caustics made them in most frames (so the soak
 *   exercised them).
 */
#ifndef StressSoak_h
#define StressSoak_h

#include <string>

namespace stress
{
/**
 * Allowed growth of RSS and heap after the warm-up, bytes. On llvmpipe the
 * screen-space technique's textures (70 MiB at 128 x 128) live in the heap and are
 * reallocated at every resize, which moves RSS by up to 15 MiB from frame to frame
 * (1000-frame soak: the peak of the last half 10.7 MiB above that of the first
 * quarter, with no trend in the heap); a leak of 25 KB a frame exceeds the bound
 * within 1000 frames.
 */
constexpr double MemoryGrowthBound = 24.0 * 1024 * 1024;

/**
 * Soaks `technique` (every registered technique when empty); true if all stayed
 * flat. `verbose` prints every frame's figures.
 */
bool RunSoak(int frames, const std::string& technique, bool verbose);
}

#endif
