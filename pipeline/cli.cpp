#include "pipeline/cli.h"

#include <tbb/global_control.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "config/command_line.h"
#include "foundation/errors.h"
#include "foundation/message_lines.h"
#include "pipeline/distributed/mpi_launch.h"
#include "pipeline/distributed/rank_start.h"
#include "pipeline/interrupts.h"
#include "pipeline/render_command.h"
#include "pipeline/retime.h"
#include "pipeline/scene_info.h"

namespace sl {

int run_cli(int argc, char** argv) {
    if (argc <= 1) {  // `slowlight` alone: what it can do
        // The one error line on stderr (as for any bad command line), the commands on stdout.
        std::fprintf(stderr, "error: command line: no command given (expected render, info or retime)\n");
        std::cout << commands_text();
        return 2;
    }
    // Under an MPI launcher with several processes: MPI, through its plugin (else nothing).
    DistributedStart dist = start_distributed(argc, argv);
    if (!dist.error.empty()) {
        if (dist.report_error) std::fprintf(stderr, "%s\n", message_line("error: ", dist.error).c_str());
        return 1;
    }
    const RankSetup ranks{dist.exchange.get(), dist.concurrent_channels};
    const bool root = !ranks.ex || ranks.ex->rank() == 0;
    interrupt_lines(root);
    // A failure: one line and the exit status; under MPI agreed with the other ranks before the
    // render starts (rank 0 prints it), and after that the failing rank ends the job.
    auto fail = [&](int code, const std::string& message) -> int {
        if (!ranks.ex) {
            std::fprintf(stderr, "%s\n", message_line("error: ", message).c_str());
            return code;
        }
        if (!have_ranks_started()) return agree_to_start(*ranks.ex, code, message);
        std::fprintf(stderr, "%s\n", message_line(("error: rank " + std::to_string(ranks.ex->rank()) + ": ").c_str(), message).c_str());
        ranks.ex->abort(code);
        return code;  // not reached: abort ends the process
    };
    try {
        RunOptions o = parse_command_line(argc, argv);
        const bool quiet = !root;  // one answer from the job, rank 0's
        switch (o.command) {
        case RunOptions::Command::Help: if (!quiet) std::cout << usage_text(o.help_topic); return 0;
        case RunOptions::Command::Version:
            if (!quiet) std::cout << "slowlight " << SLOWLIGHT_VERSION << "\n";
            return 0;
        case RunOptions::Command::Info: {
            SceneDesc scene = load_scene(o);
            if (ranks.ex) o.ranks = ranks.ex->ranks();
            if (!quiet) print_scene_info(std::cout, std::cerr, scene, o);
            return 0;
        }
        case RunOptions::Command::Retime:
            if (ranks.ex) throw InputError("command line: retime runs in one process; start it without mpirun");
            break;
        case RunOptions::Command::Render: break;
        }
        std::unique_ptr<tbb::global_control> threads;
        if (o.threads > 0)
            threads = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        if (o.command == RunOptions::Command::Retime) return retime(o);
        return render_command(o, std::vector<std::string>(argv, argv + argc), ranks);
    } catch (const InputError& e) {
        return fail(2, e.what());
    } catch (const std::bad_alloc&) {
        return fail(1, "out of memory");
    } catch (const std::exception& e) {
        return fail(1, e.what());
    }
}

}  // namespace sl
