// ecorail-montecarlo-mpi: `ecorail montecarlo` over MPI ranks, on one machine or many.
//
//   mpirun -np N ecorail-montecarlo-mpi [--ecorail PATH] MONTECARLO-ARGS...
//
// MONTECARLO-ARGS are those of `ecorail montecarlo` (--plan/--reference, --days, --seed, ...,
// --json, --csv, --svg-prefix). Rank r runs `ecorail montecarlo ... --shard r+1/N` into a private
// temporary JSON (its days only; threads as --threads says), the shard files travel to rank 0
// over MPI (no shared file system needed), and rank 0 runs `ecorail montecarlo merge` with the
// outputs asked for. The statistics are those of a single run to the last digit: every day's
// delays are keyed by (seed, day, train, station) and the merge reduces in day order. The
// program is the ecorail program next to this one unless --ecorail names another. Exit code:
// the first failing step's (2 for bad input), else 0.
#include <mpi.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

extern char** environ;

namespace {

int run(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  pid_t pid = 0;
  if (posix_spawn(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) {
    std::fprintf(stderr, "ecorail-montecarlo-mpi: error: cannot start %s\n", argv[0]);
    return 1;
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return 1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

std::string self_directory() {
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  std::string path(buf, static_cast<std::size_t>(n));
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  std::string ecorail = self_directory() + "/ecorail";
  std::vector<std::string> pass;     // to every shard
  std::vector<std::string> outputs;  // to the merge
  bool bad = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool output = a == "--json" || a == "--csv" || a == "--svg-prefix";
    if (a == "--ecorail" || output) {
      if (i + 1 >= argc) {
        if (rank == 0)
          std::fprintf(stderr, "ecorail-montecarlo-mpi: error: %s needs a value\n", a.c_str());
        bad = true;
        break;
      }
      if (a == "--ecorail")
        ecorail = argv[++i];
      else {
        outputs.push_back(a);
        outputs.push_back(argv[++i]);
      }
    } else if (a == "--shard" || a.rfind("--shard=", 0) == 0) {
      if (rank == 0)
        std::fprintf(stderr, "ecorail-montecarlo-mpi: error: --shard: the ranks are the shards\n");
      bad = true;
      break;
    } else {
      pass.push_back(a);
    }
  }
  if (bad) {
    MPI_Finalize();
    return 2;
  }
  char dir_template[] = "/tmp/ecorail-mpi-XXXXXX";
  const char* dir = mkdtemp(dir_template);
  int code = dir == nullptr ? 1 : 0;
  const std::string shard_file = std::string(dir != nullptr ? dir : "/tmp") + "/shard.json";
  if (code == 0) {
    std::vector<std::string> args = {ecorail, "montecarlo"};
    args.insert(args.end(), pass.begin(), pass.end());
    args.insert(args.end(), {"--shard", std::to_string(rank + 1) + "/" + std::to_string(size),
                             "--json", shard_file, "--quiet"});
    // Only rank 0 prints the shard's report; the others would repeat the same lines.
    if (rank != 0) {
      if (!std::freopen("/dev/null", "w", stdout)) code = 1;
    }
    if (code == 0) code = run(args);
  }
  int worst = 0;
  MPI_Allreduce(&code, &worst, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  std::string content;
  if (worst == 0) {
    std::ifstream in(shard_file);
    std::ostringstream s;
    s << in.rdbuf();
    content = s.str();
  }
  // The shard files to rank 0: lengths, then the bytes.
  int length = static_cast<int>(content.size());
  std::vector<int> lengths(static_cast<std::size_t>(size), 0),
      offsets(static_cast<std::size_t>(size), 0);
  MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
  long total = 0;
  for (int r = 0; r < size; ++r) {
    offsets[static_cast<std::size_t>(r)] = static_cast<int>(total);
    total += lengths[static_cast<std::size_t>(r)];
  }
  std::vector<char> all(rank == 0 ? static_cast<std::size_t>(total) + 1 : 1);
  MPI_Gatherv(content.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(),
              MPI_CHAR, 0, MPI_COMM_WORLD);
  if (rank == 0 && worst == 0) {
    std::vector<std::string> merge = {ecorail, "montecarlo", "merge"};
    for (int r = 0; r < size; ++r) {
      const std::string f = std::string(dir) + "/rank" + std::to_string(r) + ".json";
      std::ofstream out(f, std::ios::binary);
      out.write(all.data() + offsets[static_cast<std::size_t>(r)],
                lengths[static_cast<std::size_t>(r)]);
      merge.push_back(f);
    }
    merge.insert(merge.end(), outputs.begin(), outputs.end());
    worst = run(merge);
  }
  if (dir != nullptr) {
    std::remove(shard_file.c_str());
    if (rank == 0)
      for (int r = 0; r < size; ++r)
        std::remove((std::string(dir) + "/rank" + std::to_string(r) + ".json").c_str());
    rmdir(dir);
  }
  MPI_Bcast(&worst, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Finalize();
  return worst;
}
