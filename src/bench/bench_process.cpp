// Child processes of the benchmarks: forked measurements, mesh generation and the Python peers.
#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "bench/bench_common.h"
#include "common/error.h"
#include "common/file_util.h"
#include "common/timer.h"
#include "io/mesh_io.h"

extern char** environ;

namespace sm::app::bench {
namespace {

void writeAll(int fd, const std::string& s) {
  size_t done = 0;
  while (done < s.size()) {
    ssize_t n = ::write(fd, s.data() + done, s.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    done += size_t(n);
  }
}

std::string readAll(int fd) {
  std::string out;
  char buf[65536];
  for (;;) {
    ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    out.append(buf, size_t(n));
  }
  return out;
}

[[noreturn]] void childMain(int fd, const std::function<nlohmann::json()>& fn) {
  std::string out;
  int code = 0;
  try {
    out = fn().dump();
  } catch (const std::exception& e) {
    out = nlohmann::json{{"child_error", e.what()}}.dump();
    code = 1;
  } catch (...) {
    out = nlohmann::json{{"child_error", "unknown exception"}}.dump();
    code = 1;
  }
  writeAll(fd, out);
  ::close(fd);
  std::fflush(nullptr);
  // No destructors or atexit handlers of the parent's state in the child.
  _exit(code);
}

bool onPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (!path) return false;
  std::string dirs = path;
  size_t b = 0;
  while (b <= dirs.size()) {
    size_t e = dirs.find(':', b);
    if (e == std::string::npos) e = dirs.size();
    std::string candidate = joinPath(dirs.substr(b, e - b), program);
    if (::access(candidate.c_str(), X_OK) == 0) return true;
    b = e + 1;
  }
  return false;
}

// Beside an installed tool (share/shellmarch/bench), then the source tree it was built from.
std::string scriptPath(const std::string& file) {
  std::vector<std::filesystem::path> dirs;
  if (const char* env = std::getenv("SHELLMARCH_BENCH_SCRIPTS")) dirs.emplace_back(env);
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) dirs.push_back(exe.parent_path() / ".." / "share" / "shellmarch" / "bench");
  dirs.emplace_back(SHELLMARCH_BENCH_SCRIPT_DIR);
  for (const auto& d : dirs)
    if (fileExists((d / file).string())) return (d / file).string();
  throw Error("cannot find the benchmark script ", file, " (looked in $SHELLMARCH_BENCH_SCRIPTS, ",
              dirs.size() > 1 ? dirs[dirs.size() - 2].string() : "", " and ",
              SHELLMARCH_BENCH_SCRIPT_DIR, ")");
}

std::string logTail(const std::string& logPath) {
  std::string text;
  try {
    text = readTextFile(logPath);
  } catch (const Error&) {
    return "";
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  if (text.size() > 600) text = "..." + text.substr(text.size() - 600);
  return text;
}

}  // namespace

SpawnResult spawnLogged(const std::vector<std::string>& argv, const std::string& logPath,
                        const std::vector<std::string>& env) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, logPath.c_str(), O_WRONLY | O_CREAT | O_TRUNC,
                                   0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  std::vector<char*> envp;
  for (const auto& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  for (char** e = environ; *e; ++e) {
    const char* eq = std::strchr(*e, '=');
    const size_t n = eq ? size_t(eq - *e) + 1 : std::strlen(*e);
    if (std::none_of(env.begin(), env.end(),
                     [&](const std::string& x) { return x.compare(0, n, *e, n) == 0; }))
      envp.push_back(*e);
  }
  envp.push_back(nullptr);
  std::fflush(nullptr);
  pid_t pid = 0;
  int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), envp.data());
  posix_spawn_file_actions_destroy(&actions);
  SpawnResult r;
  if (rc != 0) return r;
  // wait4, not waitpid: its rusage holds the peak resident size of the child and of every
  // descendant it reaped, so mpirun's is its largest rank's (Linux: ru_maxrss in KiB).
  int status = 0;
  rusage usage{};
  while (wait4(pid, &status, 0, &usage) < 0 && errno == EINTR) {
  }
  r.peakRssBytes = uint64_t(usage.ru_maxrss) * 1024;
  r.status =
      WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
  return r;
}

nlohmann::json runInChild(const std::function<nlohmann::json()>& fn) {
  int fds[2];
  if (::pipe(fds) != 0) throw Error("pipe: ", std::strerror(errno));
  std::fflush(nullptr);
  pid_t pid = ::fork();
  if (pid < 0) throw Error("fork: ", std::strerror(errno));
  if (pid == 0) {
    ::close(fds[0]);
    childMain(fds[1], fn);
  }
  ::close(fds[1]);
  std::string text = readAll(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status))
    throw Error("a benchmark child process was killed by signal ", WTERMSIG(status),
                WTERMSIG(status) == SIGKILL ? " (out of memory?)" : "");
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded()) throw Error("a benchmark child process returned no result");
  if (j.contains("child_error")) throw Error(j["child_error"].get<std::string>());
  return j;
}

gen::CfdMeshOptions demoMeshOptions() {
  gen::CfdMeshOptions o;
  o.targetElements = 300000;
  o.clusters = 8;
  o.steps = 4;
  o.hexBlock = true;
  return o;
}

std::string generatedMesh(const std::string& workDir, const gen::CfdMeshOptions& o) {
  std::string name =
      concat(o.body == gen::Body::Lander ? "lander" : "capsule", "-", o.targetElements, "-c",
             o.clusters, "-s", o.steps, o.hexBlock ? "-hex" : "", "-seed", o.seed, ".pvtu");
  std::string path = joinPath(workDir, name);
  if (fileExists(path)) return path;
  std::filesystem::create_directories(workDir);
  std::fprintf(stderr,
               "generating %s with gmsh (minutes for millions of elements; kept for later runs)\n",
               path.c_str());
  Timer t;
  nlohmann::json r = runInChild([&] {
    mesh::UnstructuredMesh m = gen::generateCfdMesh(o);
    io::writePvtu(path, m);
    return nlohmann::json{{"elements", m.numCells()}};
  });
  std::fprintf(stderr, "generated %s: %llu elements in %.0f s\n", path.c_str(),
               (unsigned long long)r["elements"].get<uint64_t>(), t.seconds());
  return path;
}

ProcessResult runProcess(const std::vector<std::string>& argv, const std::vector<std::string>& env,
                         const std::string& logPath) {
  const auto start = std::chrono::steady_clock::now();
  ProcessResult r;
  r.status = spawnLogged(argv, logPath, env).status;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (r.status != 0)
    r.error = r.status < 0 ? concat("could not start ", argv[0]) : logTail(logPath);
  return r;
}

PeerRun runPeer(const PeerOptions& o) {
  PeerRun run;
  std::string script;
  try {
    script = scriptPath(o.script);
  } catch (const Error& e) {
    run.error = e.what();
    return run;
  }
  std::vector<std::string> argv;
  if (o.needsDisplay && !std::getenv("DISPLAY") && onPath("xvfb-run"))
    argv = {"xvfb-run", "-a", "-s", "-screen 0 1280x1024x24"};
  argv.push_back(o.python);
  argv.push_back(script);
  argv.insert(argv.end(), o.args.begin(), o.args.end());
  argv.push_back("--json");
  argv.push_back(o.jsonOut);
  std::remove(o.jsonOut.c_str());
  const ProcessResult p = runProcess(argv, {}, o.logPath);
  run.seconds = p.seconds;
  if (p.status != 0) {
    run.error =
        p.status < 0 ? p.error : concat(o.script, " exited with status ", p.status, ": ", p.error);
    return run;
  }
  try {
    run.result = nlohmann::json::parse(readTextFile(o.jsonOut));
    run.ok = true;
  } catch (const std::exception& e) {
    run.error = concat(o.script, " wrote no readable result: ", e.what());
  }
  return run;
}

std::string defaultPython() {
  return fileExists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
}

}  // namespace sm::app::bench
