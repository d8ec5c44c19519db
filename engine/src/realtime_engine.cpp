#include "archet/engine/realtime_engine.hpp"

#include <filesystem>
#include <string>

#include "archet/common/input_error.hpp"
#include "archet/common/printable_text.hpp"
#include "archet/interruption.hpp"
#include "archet/ipc/shared_segment.hpp"
#include "control_thread.hpp"

namespace archet {

int run_engine(const EngineOptions& options) {
    // SIGINT, SIGTERM, SIGHUP end the loop and the takes finish; a second one too (the
    // studio's death signal and a terminal's may both come) leaves the clean-up to finish.
    const InterruptionGuard stop_on_signal(/*second_ends_at_once=*/false);
    ipc::SharedSegment segment = ipc::SharedSegment::attach(options.segment);
    // Read once: whatever is written into the header later, this is the studio watched.
    const std::int32_t studio_pid =
        options.studio_pid > 0 ? options.studio_pid : segment.header().studio_pid;
    if (studio_pid <= 1)
        throw InputError("segment " + options.segment,
                         "names no studio process (owner pid " + std::to_string(studio_pid) +
                             "): give the studio's pid with --studio-pid");
    if (!options.takes.empty() && !std::filesystem::path(options.takes).is_absolute())
        throw InputError("--takes " + quoted_text(options.takes),
                         "the take directory must be an absolute path");
    ControlThread control(std::move(segment), options, studio_pid);
    return control.nrt_run();
}

}  // namespace archet
