#include "sim/membrane/model/stiffness.hpp"

#include "tests/sim/membrane/test_material.hpp"

#include "common/error.hpp"

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace ligsim::membrane {
namespace {

/// Voigt index of the tensor pair (i, j): 00 -> 0, 11 -> 1, 01 and 10 -> 2.
int voigt(int i, int j)
{
  return i == j ? i : 2;
}

/// C(theta) by rotating the fourth-order tensor of the fiber-frame stiffness, independently
/// of the closed form: C'_ijkl = R_ia R_jb R_kc R_ld C_abcd, with R's columns the fiber and
/// transverse directions. With engineering shear in Voigt form, C_ijkl = Q[voigt(ij), voigt(kl)].
Eigen::Matrix3d tensor_rotation(const Eigen::Matrix3d& q, double theta)
{
  Eigen::Matrix2d r;
  r << std::cos(theta), -std::sin(theta), std::sin(theta), std::cos(theta);
  Eigen::Matrix3d out = Eigen::Matrix3d::Zero();
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) {
          double sum = 0.0;
          for (int a = 0; a < 2; ++a)
            for (int b = 0; b < 2; ++b)
              for (int c = 0; c < 2; ++c)
                for (int d = 0; d < 2; ++d)
                  sum += r(i, a) * r(j, b) * r(k, c) * r(l, d) * q(voigt(a, b), voigt(c, d));
          out(voigt(i, j), voigt(k, l)) = sum;
        }
  return out;
}

TEST(MembraneStiffness, EqualsTheFiberFrameStiffnessRotatedAsATensor)
{
  const MembraneMaterial m = test::lens_like_material(1e-9);
  const Eigen::Matrix3d q = fiber_frame_stiffness(m);
  for (double degrees = -180.0; degrees <= 180.0; degrees += 7.5) {
    const double theta = degrees * M_PI / 180.0;
    const Eigen::Matrix3d expected = tensor_rotation(q, theta);
    const Eigen::Matrix3d actual = rotated_stiffness(m, theta);
    EXPECT_LT((actual - expected).norm(), 1e-12 * q.norm()) << "theta " << degrees << " deg";
  }
}

TEST(MembraneStiffness, FiberFrameStiffnessInvertsTheCompliance)
{
  // Plane-stress compliance of the fiber frame: eps_F = sigma_F / E_F - nu_F sigma_T / E_F, ...
  const MembraneMaterial m = test::lens_like_material(1e-9);
  Eigen::Matrix3d compliance = Eigen::Matrix3d::Zero();
  compliance(0, 0) = 1.0 / m.fiber_modulus_mpa;
  compliance(1, 1) = 1.0 / m.transverse_modulus_mpa;
  compliance(0, 1) = compliance(1, 0) = -m.fiber_poisson / m.fiber_modulus_mpa;
  compliance(2, 2) = 1.0 / m.shear_modulus_mpa;
  EXPECT_LT((fiber_frame_stiffness(m) * compliance - Eigen::Matrix3d::Identity()).norm(), 1e-12);
}

TEST(MembraneStiffness, IsSymmetricPositiveDefiniteForValidParameters)
{
  std::mt19937 random(5);
  std::uniform_real_distribution<double> modulus(0.1, 100.0), unit(0.0, 1.0), angle(-M_PI, M_PI);
  for (int trial = 0; trial < 500; ++trial) {
    MembraneMaterial m = test::lens_like_material(1e-9);
    m.fiber_modulus_mpa = modulus(random);
    m.transverse_modulus_mpa = modulus(random);
    m.shear_modulus_mpa = modulus(random);
    // Any nu_F with nu_F^2 E_T / E_F < 1 is valid; take up to 99 % of the bound.
    const double bound = std::sqrt(m.fiber_modulus_mpa / m.transverse_modulus_mpa);
    m.fiber_poisson = (2.0 * unit(random) - 1.0) * 0.99 * bound;
    ASSERT_NO_THROW(validate(m, "test"));
    const Eigen::Matrix3d c = rotated_stiffness(m, angle(random));
    EXPECT_LT((c - c.transpose()).norm(), 1e-12 * c.norm());
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(c);
    EXPECT_GT(eigen.eigenvalues().minCoeff(), 0.0) << "trial " << trial;
  }
}

TEST(MembraneStiffness, ReducesToIsotropicPlaneStressWhenTheModuliAreEqual)
{
  MembraneMaterial m = test::lens_like_material(1e-9);
  const double e = 3.0, nu = 0.3;
  m.fiber_modulus_mpa = m.transverse_modulus_mpa = e;
  m.fiber_poisson = nu;
  m.shear_modulus_mpa = e / (2.0 * (1.0 + nu));
  Eigen::Matrix3d isotropic;
  isotropic << 1.0, nu, 0.0, nu, 1.0, 0.0, 0.0, 0.0, (1.0 - nu) / 2.0;
  isotropic *= e / (1.0 - nu * nu);
  for (double degrees : {0.0, 13.0, 45.0, 90.0, 137.0, -60.0})
    EXPECT_LT((rotated_stiffness(m, degrees * M_PI / 180.0) - isotropic).norm(), 1e-12 * e)
        << degrees;
}

TEST(MembraneStiffness, FiberAlongXGivesTheFiberModulusInX)
{
  const MembraneMaterial m = test::lens_like_material(1e-9);
  // Uniaxial stress along the fibers: the strain along them is sigma / E_F.
  const Eigen::Matrix3d compliance = rotated_stiffness(m, 0.0).inverse();
  EXPECT_NEAR(1.0 / compliance(0, 0), m.fiber_modulus_mpa, 1e-12);
  const Eigen::Matrix3d turned = rotated_stiffness(m, M_PI / 2.0).inverse();
  EXPECT_NEAR(1.0 / turned(0, 0), m.transverse_modulus_mpa, 1e-12);
}

TEST(MembraneMaterial, RejectsParametersWithoutPositiveDefiniteStiffness)
{
  MembraneMaterial m = test::lens_like_material(1e-9);
  m.fiber_poisson = 2.0; // nu_F nu_T = 4 * 2 / 6 > 1
  EXPECT_THROW(validate(m, "scene"), InputError);
  m = test::lens_like_material(1e-9);
  m.transverse_modulus_mpa = 0.0;
  EXPECT_THROW(validate(m, "scene"), InputError);
  m = test::lens_like_material(1e-9);
  m.thickness_mm = -1.0;
  EXPECT_THROW(validate(m, "scene"), InputError);
}

} // namespace
} // namespace ligsim::membrane
