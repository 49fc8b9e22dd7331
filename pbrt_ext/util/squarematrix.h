// pbrt_ext: 3x3 matrices for colour (the SquareMatrix<3> part of pbrt-v4's util/math.h): diagonal
// matrices, the product with an RGB or XYZ triple, and the least-squares fit of a 3x3 matrix that
// a camera sensor's XYZ-from-sensor-RGB matrix comes from.
//
// SquareMatrix<N> itself is defined once, in util/transform.h (which has the 4x4 use); this header
// adds what colour code needs, so that a colour space's matrices and a transform's are one type,
// as in pbrt-v4. Host and device: no heap, no exceptions.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/pstd.h"
#include "pbrt_ext/util/transform.h"

#include <cmath>

namespace pbrt {

// pbrt-v4's SquareMatrix<3>::Diag.
PBRT_CPU_GPU inline SquareMatrix<3> DiagonalMatrix(Float d0, Float d1, Float d2) {
    return SquareMatrix<3>(d0, 0, 0, 0, d1, 0, 0, 0, d2);
}

// pbrt-v4's Mul<Tresult>(m, v): m times the column vector v, as a Tresult (e.g. Mul<RGB>(m, xyz)).
template <typename Tresult, typename T>
PBRT_CPU_GPU inline Tresult Mul(const SquareMatrix<3> &m, const T &v) {
    Tresult r;
    for (int i = 0; i < 3; ++i) r[i] = m[i][0] * v[0] + m[i][1] * v[1] + m[i][2] * v[2];
    return r;
}

PBRT_CPU_GPU inline RGB operator*(const SquareMatrix<3> &m, const RGB &v) { return Mul<RGB>(m, v); }
PBRT_CPU_GPU inline XYZ operator*(const SquareMatrix<3> &m, const XYZ &v) { return Mul<XYZ>(m, v); }

// The M minimizing sum_r |M a_r - b_r|^2 over rows a_r = A[r], b_r = B[r], so that b ~ M a for a
// column vector a (pbrt-v4's LinearLeastSquares<3>). Solved through the normal equations
// (A^T A) X = A^T B, X = M^T, entirely in double: A^T A squares A's condition number, and camera
// responses are strongly correlated. Empty when A^T A is singular (fewer than 3 independent rows).
PBRT_CPU_GPU inline pstd::optional<SquareMatrix<3>> LinearLeastSquares(const Float A[][3],
                                                                       const Float B[][3],
                                                                       int rows) {
    double a[3][3] = {}, b[3][3] = {};  // A^T A, A^T B
    for (int r = 0; r < rows; ++r)
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j) {
                a[i][j] += double(A[r][i]) * double(A[r][j]);
                b[i][j] += double(A[r][i]) * double(B[r][j]);
            }
    // (A^T A)^-1 by cofactors; adj[i][j] is the cofactor of a[j][i].
    double adj[3][3];
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            int r0 = (j + 1) % 3, r1 = (j + 2) % 3, c0 = (i + 1) % 3, c1 = (i + 2) % 3;
            adj[i][j] = a[r0][c0] * a[r1][c1] - a[r0][c1] * a[r1][c0];
        }
    double det = a[0][0] * adj[0][0] + a[0][1] * adj[1][0] + a[0][2] * adj[2][0];
    if (!(det != 0) || !std::isfinite(det)) return {};
    // M = X^T: M[i][j] = X[j][i] = sum_k inv[j][k] b[k][i].
    SquareMatrix<3> m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
            double sum = 0;
            for (int k = 0; k < 3; ++k) sum += adj[j][k] * b[k][i];
            m[i][j] = Float(sum / det);
        }
    return m;
}

}  // namespace pbrt
