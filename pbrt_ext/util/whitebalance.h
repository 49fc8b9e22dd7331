// pbrt_ext: von Kries white balance in the Bradford cone space (pbrt-v4's LMSFromXYZ, XYZFromLMS
// and WhiteBalance, in its util/color.h).
//
// A colour seen under a source white is mapped to how it would look under a target white by
// scaling each cone response (L, M, S) by target / source. The cone responses are the Bradford
// transform's (Lam 1985, as published by Lindbloom), which pbrt-v4 uses too; XYZFromLMS is its
// published inverse. Host and device.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/squarematrix.h"

namespace pbrt {

// Bradford "sharpened" cone responses from XYZ, and back.
PBRT_CPU_GPU inline SquareMatrix<3> LMSFromXYZ() {
    return SquareMatrix<3>(0.8951, 0.2664, -0.1614,
                           -0.7502, 1.7135, 0.0367,
                           0.0389, -0.0685, 1.0296);
}
PBRT_CPU_GPU inline SquareMatrix<3> XYZFromLMS() {
    return SquareMatrix<3>(0.9869929, -0.1470543, 0.1599627,
                           0.4323053, 0.5183603, 0.0492912,
                           -0.0085287, 0.0400428, 0.9684867);
}

// The XYZ-to-XYZ matrix that takes the source white (chromaticity, any luminance) to the target
// white of the same luminance. The identity when the two are equal.
PBRT_CPU_GPU inline SquareMatrix<3> WhiteBalance(Chromaticity srcWhite, Chromaticity targetWhite) {
    XYZ src = LMSFromXYZ() * XYZ::FromxyY(srcWhite), dst = LMSFromXYZ() * XYZ::FromxyY(targetWhite);
    SquareMatrix<3> lmsCorrect = DiagonalMatrix(dst[0] / src[0], dst[1] / src[1], dst[2] / src[2]);
    return XYZFromLMS() * lmsCorrect * LMSFromXYZ();
}

}  // namespace pbrt
