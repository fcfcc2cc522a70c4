// The sparse assembly of W^T M^-1 W (sums over the bodies two contacts share) against the dense
// products over all n_dof rows, in the impact and the contact problems of a four-span bridge at
// seeded random states, index sets and slip signs.
#include "solver/contact/delassus.h"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <vector>

#include "solver/contact/contact_problem.h"
#include "solver/contact/impact_problem.h"
#include "solver/model/multispan.h"

namespace skewbridge::contact {
namespace {

model::Model FourSpans() {
  model::MultiSpanSpec spec;
  spec.n_spans = 4;
  spec.span_lengths_m = {30.0, 35.0, 35.0, 30.0};
  spec.width_m = 11.0;
  spec.skew_rad = 25.0 * std::numbers::pi / 180.0;
  spec.mass_per_length_kgpm = 18e3;
  spec.w0x_radps = spec.w0y_radps = 7.0;
  spec.W0_radps = 9.0;
  spec.abutment_gap_m = 0.02;
  spec.joint_gap_m = 0.01;
  spec.restitution = 0.6;
  spec.friction = 0.3;
  return model::BuildMultiSpanBridge(spec, "four-spans");
}

TEST(Delassus, AutoAssemblyIsDenseForOneDeckAndSparseForSeveral) {
  model::MultiSpanSpec one;
  one.n_spans = 1;
  one.span_lengths_m = {30.0};
  one.width_m = 10.0;
  one.mass_per_length_kgpm = 1e4;
  EXPECT_FALSE(UsesSparseAssembly(model::BuildMultiSpanBridge(one), Assembly::kAuto));
  EXPECT_TRUE(UsesSparseAssembly(FourSpans(), Assembly::kAuto));
  EXPECT_FALSE(UsesSparseAssembly(FourSpans(), Assembly::kDense));
}

TEST(Delassus, SparseAndDenseAssemblyGiveTheSameImpactAndContactProblems) {
  const model::Model model = FourSpans();
  const int n = model.n_dof();
  const int nc = model.n_contacts();
  ImpactProblem dense_impact(model, {}, Assembly::kDense),
      sparse_impact(model, {}, Assembly::kSparse);
  ContactProblem dense_contact(model, {}, Assembly::kDense),
      sparse_contact(model, {}, Assembly::kSparse);
  ImpactResult dense_ir = dense_impact.MakeResult(), sparse_ir = sparse_impact.MakeResult();
  ContactResult dense_cr = dense_contact.MakeResult(), sparse_cr = sparse_contact.MakeResult();
  ContactKinematics kin;
  kin.Resize(model);
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::bernoulli_distribution pick(0.5);
  for (int trial = 0; trial < 100; ++trial) {
    Eigen::VectorXd q(n), u(n), h(n);
    for (int k = 0; k < n; ++k) {
      q(k) = (k % 3 == 2 ? 0.002 : 0.01) * unit(rng);
      u(k) = (k % 3 == 2 ? 0.01 : 0.3) * unit(rng);
      h(k) = 1e6 * unit(rng);
    }
    Evaluate(model, q, u, kin);
    std::vector<int> index_set;
    std::vector<ClosedContact> closed;
    for (int c = 0; c < nc; ++c) {
      if (pick(rng)) {
        index_set.push_back(c);
        closed.push_back({c, static_cast<int>(rng() % 3) - 1});
      }
    }
    const lcp::LcpStatus ds = dense_impact.Solve(kin, index_set, u, dense_ir);
    const lcp::LcpStatus ss = sparse_impact.Solve(kin, index_set, u, sparse_ir);
    ASSERT_EQ(ds, ss);
    const Eigen::MatrixXd A_dense = dense_impact.last_A();
    const Eigen::MatrixXd A_sparse = sparse_impact.last_A();
    const double scale = A_dense.cwiseAbs().maxCoeff();
    EXPECT_LE((A_dense - A_sparse).cwiseAbs().maxCoeff(), 1e-14 * scale) << "trial " << trial;
    if (ds == lcp::LcpStatus::kSolved) {
      EXPECT_LE((dense_ir.u_E - sparse_ir.u_E).cwiseAbs().maxCoeff(),
                1e-10 * (1.0 + u.cwiseAbs().maxCoeff()));
    }
    dense_contact.Solve(kin, closed, h, dense_cr);
    sparse_contact.Solve(kin, closed, h, sparse_cr);
    const Eigen::MatrixXd C_dense = dense_contact.last_A();
    const Eigen::MatrixXd C_sparse = sparse_contact.last_A();
    const double c_scale = C_dense.size() > 0 ? C_dense.cwiseAbs().maxCoeff() : 0.0;
    EXPECT_LE((C_dense - C_sparse).cwiseAbs().maxCoeff(), 1e-14 * c_scale) << "trial " << trial;
    EXPECT_LE((dense_cr.du_dt - sparse_cr.du_dt).cwiseAbs().maxCoeff(),
              1e-9 * (1.0 + dense_cr.du_dt.cwiseAbs().maxCoeff()));
  }
}

}  // namespace
}  // namespace skewbridge::contact
