#pragma once
/// @file
/// Sparse assembly of the Delassus blocks W_a^T M^-1 W_b of the impact and contact problems
/// [docs/theory.md §3] for models of several decks. M is diagonal (planar rigid decks), and a
/// Jacobian column of a contact is non-zero only on the DOFs of the contact's two bodies (its
/// point's deck and, for a deck-to-deck contact, the face's deck), so entry (r, s) is a sum over
/// the bodies the two contacts share: at most 6 products instead of n_dof, and zero for contacts
/// on different decks. docs/multispan.md.

#include <Eigen/Core>
#include <span>

#include "solver/model/model.h"

namespace skewbridge::contact {

/// How the impact and contact problems assemble W^T M^-1 W: dense products over all n_dof rows,
/// sparse sums over shared bodies, or automatic (sparse for more than one body, so that a single
/// deck keeps the dense path bit for bit).
enum class Assembly { kAuto, kDense, kSparse };

/// Whether `assembly` selects the sparse assembly for `model`.
bool UsesSparseAssembly(const model::Model& model, Assembly assembly);

/// out = W_a^T M^-1 W_b (k_a x k_b), column r of W_a (n_dof) a Jacobian column of contact
/// contacts_a[r], column s of W_b one of contacts_b[s]: entry (r, s) =
/// sum over bodies B shared by the two contacts of W_a(3B..3B+2, r)^T M_B^-1 W_b(3B..3B+2, s).
/// No allocation.
/// @pre W_a has contacts_a.size() columns, W_b contacts_b.size(), out is k_a x k_b (SB_ASSERT).
void SparseDelassus(const model::Model& model, const Eigen::Ref<const Eigen::MatrixXd>& W_a,
                    std::span<const int> contacts_a, const Eigen::Ref<const Eigen::MatrixXd>& W_b,
                    std::span<const int> contacts_b, Eigen::Ref<Eigen::MatrixXd> out);

}  // namespace skewbridge::contact
