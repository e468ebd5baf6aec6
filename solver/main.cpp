// rksolve: explicit RKPM on N ranks, each reading only its own subdomain file.
//   mpirun -np N rksolve CASE [--set key.path=value ...] [--quiet] [--progress SECONDS] [--restart | --from PREVIOUS]
#include <mpi.h>

#include <cstdio>
#include <filesystem>

#include "cli.hpp"
#include "parallel/comm.hpp"
#include "solver.hpp"

int main(int argc, char** argv) {
  rk::ignore_file_size_signal();
  CLI::App app{"rksolve: run the explicit RKPM solution of a prepared case (mpirun -np N rksolve CASE)", "rksolve"};
  rk::add_version_flag(app);
  rk::SolveOptions options;
  std::vector<std::string> sets;
  app.add_option("case", options.case_dir, "case directory written by rkprep")->required();
  app.add_option("--set", sets, "override a solver-side scene key: key.path=value (repeatable)");
  app.add_flag("--quiet", options.quiet, "print nothing but errors");
  app.add_option("--progress", options.progress_s, "seconds between progress lines (default 2 on a terminal, 10 in a log)")
      ->check(CLI::Range(1e-3, 1e6, "a number of seconds in [0.001, 1e6]"));
  auto* restart = app.add_flag("--restart", options.restart, "continue from the newest checkpoint in CASE/checkpoint");
  app.add_option("--from", options.from,
                 "a stage of a chain: start from the final state of the case PREVIOUS (the same part; other dies, "
                 "or none for a dwell); time.end counts from its end")
      ->excludes(restart);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);  // --help and --version need no MPI
  }
  MPI_Init(&argc, &argv);
  int status = 1;
  {
    const rk::Comm comm;
    try {
      options.overrides = rk::parse_overrides(sets);
      rk::solve_case(options, comm);
      status = 0;
    } catch (const rk::Error& e) {
      // Errors reach every rank together (Comm::check); input errors are the same on every rank.
      if (comm.rank() == 0) std::fprintf(stderr, "rksolve: error: %s\n", e.what());
    } catch (const std::filesystem::filesystem_error& e) {  // a folder or file the system refused this rank
      std::fprintf(stderr, "rksolve: rank %d: error: %s: %s\n", comm.rank(), e.path1().c_str(), e.code().message().c_str());
      MPI_Abort(MPI_COMM_WORLD, 1);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "rksolve: rank %d: internal error: %s\n", comm.rank(), e.what());
      MPI_Abort(MPI_COMM_WORLD, 2);
    }
  }
  MPI_Finalize();
  return status;
}
