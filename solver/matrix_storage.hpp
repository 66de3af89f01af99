#pragma once
// Which entries of a square sparse matrix are stored (a decision shared by the sparsity pattern,
// the problems that assemble into it and the linear solver).
//
// Upper (the default): the matrix is symmetric and only the upper triangle (row <= column) is
// stored. This is what CHOLMOD reads with stype = +1, and its documentation notes that a symmetric
// matrix "stored in upper triangular form" is the fastest input when a fill-reducing ordering is
// used (cholmod_core.h, Common->prefer_upper). Half the entries also halve assembly scatter work
// and memory. The UMFPACK fallback expands the matrix to both triangles through a map built once.
//
// Full: every entry is stored. For tangents that may be non-symmetric (LU only), or symmetric
// matrices assembled in full (CHOLMOD then reads the upper triangle, UMFPACK the whole matrix).
namespace isomuscle::solver {

enum class MatrixStorage { Upper, Full };

}  // namespace isomuscle::solver
