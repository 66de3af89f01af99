#pragma once
// The number of threads of the BLAS that CHOLMOD's supernodal factorisation calls (dgemm, dsyrk,
// dpotrf on the supernodes). Debian's OpenBLAS (libopenblas0-pthread) starts one thread per core
// and its idle threads spin: on a machine whose cores are busy (the assembly's own threads, other
// jobs, a CI runner) the factorisation of a small matrix then waits for descheduled threads.
// Measured here on the 2-core machine under load: Cook's membrane 16 x 16 (1944 DOFs) numeric
// factorisation 3.3 s with OpenBLAS's default threads, 0.30 s with one; the barrel contraction
// (450 DOFs) 8.7 s and 0.97 s. The count is process-wide (a BLAS setting, not a per-solver one).
namespace isomuscle::solver {

// Sets the BLAS thread count (>= 1) when the loaded BLAS is OpenBLAS (openblas_set_num_threads
// found at run time); returns false, changing nothing, for another BLAS.
bool set_blas_threads(int threads);

// OpenBLAS's current count (openblas_get_num_threads), or 0 for another BLAS.
int blas_threads();

}  // namespace isomuscle::solver
