// Randomized reconstruction stress (issue 8, point 2): random unions of ellipsoids and tori
// (section_generator.h) sliced by random orthogonal and oblique planes, each case reconstructed
// by the real entry point, `planesketch reconstruct`, in a child process, so that a crash or a
// hang is recorded as such instead of ending the run.
//
// Every case ends in exactly one of:
//   ok         exit 0 and the output is closed, 2-manifold, outward, free of self-intersections,
//              and every input curve point lies within 1e-6 of the box diagonal of the surface;
//   violation  exit 0 but one of those guarantees fails (a bug);
//   refused    non-zero exit with a message (its first line is tallied, digits removed);
//   crash      the child died of a signal;
//   hang       the child exceeded the time limit (default 10 s wall) and was killed.
//
// Usage: recon_stress_bench [--cases N] [--first-seed S] [--timeout SEC] [--oblique-every K]
//                           [--binary PATH] [--work DIR] [--keep-failures]
// Every K-th case (default 2) adds 1-3 oblique planes; the rest are purely orthogonal.
// Prints a Markdown summary; exit status 1 when a case crashed, hung or broke a guarantee.
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "modeling/contour_io.h"
#include "modeling/mesh_io.h"
#include "modeling/mesh_queries.h"
#include "modeling/section_generator.h"

namespace fs = std::filesystem;

namespace {

struct Args {
  int cases = 100;
  std::uint64_t first_seed = 1;
  double timeout_s = 10.0;
  int oblique_every = 2;
  std::string binary = PLANESKETCH_BINARY;
  std::string work = "build/stress";
  bool keep_failures = false;
};

struct ChildResult {
  bool timed_out = false;
  int status = 0;
  double wall_s = 0, cpu_s = 0;
};

// Runs argv with stdout/stderr redirected to files; kills it after timeout_s of wall time.
ChildResult run_child(const std::vector<std::string>& argv, const std::string& out_path,
                      const std::string& err_path, double timeout_s) {
  ChildResult r;
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    if (!std::freopen(out_path.c_str(), "w", stdout) || !std::freopen(err_path.c_str(), "w", stderr)) _exit(126);
    std::vector<char*> cargv;
    for (const auto& a : argv) cargv.push_back(const_cast<char*>(a.c_str()));
    cargv.push_back(nullptr);
    execv(cargv[0], cargv.data());
    _exit(127);
  }
  if (pid < 0) {
    r.status = -1;
    return r;
  }
  struct rusage usage {};
  for (;;) {
    const pid_t w = wait4(pid, &r.status, WNOHANG, &usage);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (w == pid) {
      r.wall_s = elapsed;
      break;
    }
    if (elapsed > timeout_s) {
      kill(pid, SIGKILL);
      wait4(pid, &r.status, 0, &usage);
      r.timed_out = true;
      r.wall_s = elapsed;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  r.cpu_s = static_cast<double>(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
            1e-6 * static_cast<double>(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  return r;
}

std::string first_line(const std::string& path) {
  std::ifstream f(path);
  std::string line, last;
  // The reason is the last "planesketch:" line that is not a warning or progress line.
  while (std::getline(f, line)) {
    if (line.find("warning") != std::string::npos) continue;
    if (!line.empty()) last = line;
  }
  return last;
}

// A tally key for a refusal: the message without digits, file paths and curve numbers.
std::string reason_key(std::string message) {
  const auto colon = message.find(".json");
  if (colon != std::string::npos) message = message.substr(colon + 5);
  std::string out;
  for (const char c : message) {
    if (std::isdigit(static_cast<unsigned char>(c))) {
      if (out.empty() || out.back() != '#') out += '#';
    } else {
      out += c;
    }
  }
  if (out.size() > 110) out = out.substr(0, 110) + "...";
  return out;
}

double percentile(std::vector<double> v, double p) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const auto i = static_cast<size_t>(std::ceil(p * static_cast<double>(v.size()))) - 1;
  return v[std::min(i, v.size() - 1)];
}

}  // namespace

int main(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "recon_stress_bench: %s needs a value\n", k.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (k == "--cases") a.cases = std::stoi(next());
    else if (k == "--first-seed") a.first_seed = std::stoull(next());
    else if (k == "--timeout") a.timeout_s = std::stod(next());
    else if (k == "--oblique-every") a.oblique_every = std::stoi(next());
    else if (k == "--binary") a.binary = next();
    else if (k == "--work") a.work = next();
    else if (k == "--keep-failures") a.keep_failures = true;
    else {
      std::fprintf(stderr, "recon_stress_bench: unknown option %s\n", k.c_str());
      return 2;
    }
  }
  fs::create_directories(a.work);

  std::map<std::string, int> outcome, refusals;
  std::vector<std::string> failures;
  std::vector<double> wall, cpu;
  int ortho_cases = 0, mixed_cases = 0, ortho_ok = 0, mixed_ok = 0;
  for (int c = 0; c < a.cases; ++c) {
    const std::uint64_t seed = a.first_seed + static_cast<std::uint64_t>(c);
    ps::GeneratorOptions g;
    g.seed = seed;
    g.orthogonal_planes = 2 + static_cast<int>(seed % 5);  // 2..6
    const bool mixed = a.oblique_every > 0 && c % a.oblique_every == a.oblique_every - 1;
    g.oblique_planes = mixed ? 1 + static_cast<int>(seed % 3) : 0;
    (mixed ? mixed_cases : ortho_cases)++;
    const auto gen = ps::generate_sections(g);
    const std::string base = a.work + "/case" + std::to_string(seed);
    const std::string in = base + ".json", out = base + ".off", log_out = base + ".out", log_err = base + ".err";
    {
      std::ofstream f(in);
      f << ps::format_contour_json(gen.sections);
    }
    std::error_code ec;
    fs::remove(out, ec);
    const auto r = run_child({a.binary, "reconstruct", in, "-o", out, "--threads", "1"}, log_out, log_err, a.timeout_s);
    std::string kind, detail;
    if (r.timed_out) {
      kind = "hang";
      detail = "over " + std::to_string(a.timeout_s) + " s";
    } else if (WIFSIGNALED(r.status)) {
      kind = "crash";
      detail = std::string("signal ") + strsignal(WTERMSIG(r.status));
    } else if (WIFEXITED(r.status) && WEXITSTATUS(r.status) != 0) {
      kind = "refused";
      detail = first_line(log_err);
      refusals[reason_key(detail)]++;
    } else {
      auto mesh = ps::read_mesh(out);
      if (!mesh) {
        kind = "violation";
        detail = "output unreadable: " + mesh.message();
      } else {
        const auto guarantees = ps::check_guarantees(*mesh);
        const auto pts = gen.sections.all_points();
        const double diag = ps::bounding_box(pts).diagonal();
        const double d = ps::max_distance_to_surface(*mesh, pts);
        if (!guarantees.valid()) {
          kind = "violation";
          detail = guarantees.problem();
        } else if (d > 1e-6 * diag) {
          kind = "violation";
          detail = "curve point " + std::to_string(d / diag) + " of the diagonal off the surface";
        } else {
          kind = "ok";
          (mixed ? mixed_ok : ortho_ok)++;
        }
      }
      wall.push_back(r.wall_s);
      cpu.push_back(r.cpu_s);
    }
    outcome[kind]++;
    const bool keep = kind != "ok" && kind != "refused";
    if (kind != "ok") failures.push_back("seed " + std::to_string(seed) + (mixed ? " (mixed)" : " (orthogonal)") + ": " + kind + ": " + detail);
    if (!(keep && a.keep_failures)) {
      fs::remove(in, ec);
      fs::remove(log_out, ec);
      fs::remove(log_err, ec);
    }
    fs::remove(out, ec);
    std::fprintf(stderr, "\rcase %d/%d  ok %d  refused %d  other %d   ", c + 1, a.cases, outcome["ok"],
                 outcome["refused"], c + 1 - outcome["ok"] - outcome["refused"]);
  }
  std::fprintf(stderr, "\n");

  std::printf("## Reconstruction stress: %d cases, seeds %llu..%llu\n\n", a.cases,
              static_cast<unsigned long long>(a.first_seed),
              static_cast<unsigned long long>(a.first_seed + static_cast<std::uint64_t>(a.cases) - 1));
  std::printf("| outcome | cases |\n|---|---:|\n");
  for (const char* k : {"ok", "refused", "violation", "crash", "hang"}) std::printf("| %s | %d |\n", k, outcome[k]);
  std::printf("\nOrthogonal-only cases: %d of %d ok; cases with oblique planes: %d of %d ok.\n", ortho_ok,
              ortho_cases, mixed_ok, mixed_cases);
  std::printf("Refusal rate: %.1f%%.\n", 100.0 * outcome["refused"] / std::max(1, a.cases));
  if (!wall.empty())
    std::printf("Completed runs (exit 0): wall median %.2f s, p95 %.2f s, max %.2f s; CPU median %.2f s, p95 %.2f s, max %.2f s.\n",
                percentile(wall, 0.5), percentile(wall, 0.95), percentile(wall, 1.0), percentile(cpu, 0.5),
                percentile(cpu, 0.95), percentile(cpu, 1.0));
  if (!refusals.empty()) {
    std::printf("\n| refusal reason (digits as #) | cases |\n|---|---:|\n");
    std::vector<std::pair<int, std::string>> sorted;
    for (const auto& [k, n] : refusals) sorted.emplace_back(-n, k);
    std::sort(sorted.begin(), sorted.end());
    for (const auto& [n, k] : sorted) std::printf("| %s | %d |\n", k.c_str(), -n);
  }
  if (!failures.empty()) {
    std::printf("\nCases not ok:\n");
    for (const auto& f : failures) std::printf("- %s\n", f.c_str());
  }
  return outcome["violation"] + outcome["crash"] + outcome["hang"] > 0 ? 1 : 0;
}
