#include "solver/contact/delassus.h"

#include "solver/common/error.h"

namespace skewbridge::contact {

bool UsesSparseAssembly(const model::Model& model, Assembly assembly) {
  return assembly == Assembly::kSparse || (assembly == Assembly::kAuto && model.n_bodies() > 1);
}

void SparseDelassus(const model::Model& model, const Eigen::Ref<const Eigen::MatrixXd>& W_a,
                    std::span<const int> contacts_a, const Eigen::Ref<const Eigen::MatrixXd>& W_b,
                    std::span<const int> contacts_b, Eigen::Ref<Eigen::MatrixXd> out) {
  const Eigen::Index ka = static_cast<Eigen::Index>(contacts_a.size());
  const Eigen::Index kb = static_cast<Eigen::Index>(contacts_b.size());
  SB_ASSERT(W_a.cols() == ka && W_b.cols() == kb, "one contact per Jacobian column");
  SB_ASSERT(out.rows() == ka && out.cols() == kb, "Delassus block has the wrong size");
  const Eigen::VectorXd& Minv = model.inverse_mass_diagonal();
  for (Eigen::Index r = 0; r < ka; ++r) {
    const model::Contact& a = model.contact(contacts_a[static_cast<std::size_t>(r)]);
    const int bodies_a[2] = {a.body, a.face.body};
    for (Eigen::Index s = 0; s < kb; ++s) {
      const model::Contact& b = model.contact(contacts_b[static_cast<std::size_t>(s)]);
      double sum = 0.0;
      for (int body : bodies_a) {
        if (body == model::kGround || (body != b.body && body != b.face.body)) {
          continue;
        }
        const int d = 3 * body;
        sum +=
            W_a.col(r).segment<3>(d).dot(Minv.segment<3>(d).cwiseProduct(W_b.col(s).segment<3>(d)));
      }
      out(r, s) = sum;
    }
  }
}

}  // namespace skewbridge::contact
