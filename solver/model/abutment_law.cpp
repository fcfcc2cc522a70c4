#include "solver/model/abutment_law.h"

#include <cmath>

namespace skewbridge::model {

double WallLength_m(const DeckGeometry& deck) { return (Corner(deck, 1) - Corner(deck, 2)).norm(); }

joint::HyperbolicGap WallBackfill(const BackfillSpec& spec, const DeckGeometry& deck,
                                  std::string_view source) {
  switch (spec.form) {
    case BackfillForm::kHyperbolicGap: {
      const double per = spec.per_metre ? WallLength_m(deck) : 1.0;
      joint::HyperbolicGap law;
      law.k_max_N_per_m = spec.k_max * per;
      law.k_ur_N_per_m = spec.k_ur * per;
      law.r_f = spec.r_f;
      law.f_ult_N = spec.f_ult * per;
      law.gap_m = 0.0;
      joint::ValidateHyperbolicGap(law, source);
      return law;
    }
    case BackfillForm::kShamsabadi:
      return joint::FromShamsabadi(spec.k50_Npm, spec.f_ult, spec.y_max_m, 0.0, source);
    case BackfillForm::kCaltrans: {
      const double r_sk = spec.skew_reduction ? joint::CaltransSkewFactor(deck.skew_rad) : 1.0;
      const joint::CaltransAbutment c = joint::CaltransSdc2(spec.width_m, spec.height_m, r_sk);
      return joint::FromInitialStiffness(c.k_initial_N_per_m, c.p_bw_N, spec.y_max_m, 0.0, source);
    }
  }
  return {};
}

}  // namespace skewbridge::model
