// A C++ supervisor of the tiny corpus project: its run says which Webots header is missing.
#include <webots/Supervisor.hpp>

int main() {
  webots::Supervisor supervisor;
  while (supervisor.step(32) != -1) {
  }
  return 0;
}
