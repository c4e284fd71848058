#pragma once
// One render over every rank of a Session. The image is split by 16x16 tiles, dealt round robin (tile t to rank
// t mod N: neighbouring tiles cost about the same, so every rank gets a similar share of every region). A pixel's
// samples depend only on the seed and the pixel (its own PCG32 stream), never on who renders it, and each pixel is
// rendered by exactly one rank; rank 0 sums the films, where every pixel is x + 0 + ... + 0 = x, so the image is
// bit-identical to the single-process render with the same seed, for any number of ranks and threads.
//
// Rank 0 draws one progress bar for all ranks (the others report their pixel samples every 0.2 s). Ctrl-C (SIGINT,
// or mpirun's SIGTERM to every rank) stops every rank's threads before their next sample (render/integrator.hpp);
// the films, which count each pixel's samples, are summed as usual, so rank 0 writes the image accumulated so far
// on every rank. A rank whose render throws ends the whole
// run (Session::abort: the message names the rank and its error).
#include "surfscatter/distributed/session.hpp"
#include "surfscatter/render/integrator.hpp"

namespace surfscatter::distributed {

// Collective. Returns the whole film on rank 0 (an empty film of the same size elsewhere). `stats` on rank 0:
// samples per pixel and rays over all ranks, interrupted if any rank was.
render::Film render(const Session& session, const render::Scene& scene, const render::RenderOptions& options,
                    render::RenderStats* stats = nullptr);

}  // namespace surfscatter::distributed
