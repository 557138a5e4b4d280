// Output-error formulation by multiple shooting: every run of used intervals is cut into
// segments of a few rows; each segment starts from a free speed (a shooting node), the model is
// integrated through the segment with the logged forces (motion_model.hpp), and every row's
// logged speed is compared with the simulated one, one residual per row under the robust loss.
// A soft continuity residual ties the end of each segment to the node of the next, so a run
// behaves as one simulated trajectory while the short segments keep the problem well
// conditioned. Because each residual belongs to one row, the discounted rows are read directly
// from the loss weights.
#pragma once

#include <memory>

#include "fitting/formulation.hpp"

namespace ecorail::fitting {

struct OutputErrorOptions {
  int segment_rows = 10;              // rows per shooting segment
  double continuity_fraction = 0.05;  // continuity tolerance as a fraction of the noise scale
};

std::unique_ptr<Formulation> make_output_error(const PreparedData& data,
                                               const ModelConstants& constants,
                                               const OutputErrorOptions& options);

}  // namespace ecorail::fitting
