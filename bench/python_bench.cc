// The Python module's overhead (issue 16): lfsp.segment called from Python on antinous against the same library
// call from C++ (segment/lfsp-antinous). The Python interpreter is started and the light field loaded once, untimed,
// in a worker process; each timed run asks it for one lfsp.segment call and waits for the answer.

#include <sys/types.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <stdexcept>
#include <string>

#include "bench_case.h"

namespace lfsp::bench {
namespace {

// Reads the light field and its disparity, says "ready", then runs lfsp.segment once per line it is sent.
constexpr const char* kWorkerScript = R"py(
import resource, sys, lfsp
lf = lfsp.read(sys.argv[1])
disparity = lf.disparity
print("ready", flush=True)
for line in sys.stdin:
    labels = lfsp.segment(lf, disparity, size=20)
    peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
    print(f"labels={int(labels.max()) + 1} views={labels.shape[0]}x{labels.shape[1]}; "
          f"Python worker's peak {peak_mb:.0f} MB (the peak column is the bench process alone)", flush=True)
)py";

class PythonWorker {
 public:
  void Start(const std::string& light_field) {
    int to_worker[2], from_worker[2];
    if (pipe(to_worker) != 0 || pipe(from_worker) != 0) throw std::runtime_error("pipe failed");
    const pid_t pid = fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
      dup2(to_worker[0], STDIN_FILENO);
      dup2(from_worker[1], STDOUT_FILENO);
      close(to_worker[1]);
      close(from_worker[0]);
      setenv("PYTHONPATH", LFSP_PYTHON_PATH, 1);
      execl(LFSP_PYTHON_EXECUTABLE, LFSP_PYTHON_EXECUTABLE, "-c", kWorkerScript, light_field.c_str(),
            static_cast<char*>(nullptr));
      _exit(127);
    }
    close(to_worker[0]);
    close(from_worker[1]);
    requests_ = fdopen(to_worker[1], "w");
    answers_ = fdopen(from_worker[0], "r");
    if (ReadLine() != "ready") throw std::runtime_error("the Python worker did not start");
  }

  std::string RunOnce() {
    std::fputs("segment\n", requests_);
    std::fflush(requests_);
    return ReadLine();
  }

 private:
  std::string ReadLine() {
    char line[256];
    if (std::fgets(line, sizeof line, answers_) == nullptr) throw std::runtime_error("the Python worker stopped");
    std::string text = line;
    if (!text.empty() && text.back() == '\n') text.pop_back();
    return text;
  }

  FILE* requests_ = nullptr;
  FILE* answers_ = nullptr;
};

PythonWorker& Worker() {
  static PythonWorker worker;
  return worker;
}

}  // namespace

LFSP_BENCH_CASE {
  BenchCase c;
  c.stage = "python";
  c.name = "lfsp-antinous-from-python";
  c.input = "antinous 9x9x512x512, size 20, GT disparity; lfsp.segment(lf, disparity)";
  c.target = "<= 1.02 x lfsp-antinous (C++)";
  c.needs_shared_data = true;
  c.baseline = "lfsp-antinous";
  c.repetitions = 3;
  c.prepare = [] { Worker().Start(SharedDataDir() + "/hci/antinous"); };
  c.run = [] { return Worker().RunOnce(); };
  return c;
}

}  // namespace lfsp::bench
