// Distributed reference rendering over MPI (OpenMPI): when tandem runs under `mpirun`, each
// process renders its stripes of rows and rank 0 sums the partial images (reference_render.h).
#pragma once
#include <memory>

#include "rt/reference_render.h"

namespace tandem {

// True when the environment says an MPI launcher started this process.
bool launchedByMpi();
// The MPI world as a SampleCluster when launched by mpirun; null for a plain run. Throws when
// launched by mpirun but built without MPI. Initialises MPI (finalised with the object).
std::unique_ptr<SampleCluster> makeMpiCluster();

}  // namespace tandem
