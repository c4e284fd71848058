#pragma once
// The typedefs Eigen's (unsupported) Levenberg-Marquardt asks of a residual functor with run-time sizes; the KC fits
// (kc_fit.cpp, elliptical_fit.cpp) derive from it.
#include <Eigen/Core>

namespace surfscatter::surface {

struct DynamicLeastSquaresFunctor {
    using Scalar = double;
    enum { InputsAtCompileTime = Eigen::Dynamic, ValuesAtCompileTime = Eigen::Dynamic };
    using InputType = Eigen::VectorXd;
    using ValueType = Eigen::VectorXd;
    using JacobianType = Eigen::MatrixXd;
};

}  // namespace surfscatter::surface
