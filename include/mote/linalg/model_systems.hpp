// Model systems for validating and measuring the sparse solvers (VALIDATION
// D1: problems/linear_solver, tests/unit/test_linalg_solver.cpp):
//  - the 5-point stencil on an n x n grid (row = i + n j) with
//    -Laplace(u) + c . grad(u) on the unit square, h = 1 / (n + 1), central
//    differences for the convection (non-symmetric; cell Peclet number
//    |c| h / 2), Dirichlet sides;
//  - a tridiagonal pattern with tridiag(-1, diagonal, +1), nearly
//    skew-symmetric for a small diagonal, on which plain BiCGStab stalls.
// Patterns are built once; the value functions fill a matrix on them.
#pragma once

#include "mote/linalg/crs_pattern.hpp"

namespace mote::linalg {

/// The 5-point pattern on an n x n grid, row = i + n j, columns ascending.
CrsPattern five_point_pattern(int n);
/// scale x (-Laplace(u) + (cx, cy) . grad(u)) on five_point_pattern(n).
void convection_diffusion_values(const CrsMatrix& A, int n, double cx, double cy, double scale = 1.0);
/// The tridiagonal pattern of n rows.
CrsPattern tridiagonal_pattern(int n);
/// tridiag(-1, diagonal, +1) on tridiagonal_pattern(n).
void near_skew_values(const CrsMatrix& A, double diagonal);

}  // namespace mote::linalg
