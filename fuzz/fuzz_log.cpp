// The per-second logs calibrate reads (published tables and plain CSV): parsed, checked for
// plausibility against the reference train and prepared for a fit (conversion and interval
// classification), which is where a speed of 1e308 once crashed.
#include <vector>

#include "data/train_io.hpp"
#include "fitting/log_plausibility.hpp"
#include "fitting/log_prep.hpp"
#include "fitting/log_reader.hpp"
#include "fuzz_support.hpp"

using namespace ecorail;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const physics::Train train = data::default_train();
  fuzz::refuse_cleanly([&] {
    const std::vector<fitting::Log> logs{fitting::parse_log(fuzz::as_text(data, size), "log.csv")};
    fitting::check_logs_plausible(logs, train);
    fitting::prepare_logs(logs, train, fitting::PrepOptions{});
  });
  return 0;
}
