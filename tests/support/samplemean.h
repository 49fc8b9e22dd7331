// The mean of independent estimates and its standard error, and the z score of two such means'
// difference, for tests that compare estimators sample by sample.
#pragma once

#include <cmath>
#include <vector>

namespace pbrt {

struct MeanAndError {
    double mean = 0, standardError = 0;
};

inline MeanAndError MeanOf(const std::vector<double> &values) {
    double sum = 0, sumOfSquares = 0;
    for (double v : values) {
        sum += v;
        sumOfSquares += v * v;
    }
    const double n = double(values.size()), mean = sum / n;
    return {mean, std::sqrt((sumOfSquares / n - mean * mean) / (n - 1))};
}

// The difference of two means in standard errors of the difference.
inline double DifferenceZ(const MeanAndError &a, const MeanAndError &b) {
    return (a.mean - b.mean) / std::hypot(a.standardError, b.standardError);
}

}  // namespace pbrt
