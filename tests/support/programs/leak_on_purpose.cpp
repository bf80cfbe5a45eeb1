// A program that leaks on purpose, built with the sanitizer tree's bss
// prefault (cmake/sanitizer_prefault.cpp): its test checks that
// LeakSanitizer still reports a leak after the prefault mapped the bss.
// The only pointer to the block was in the bss, and is gone.
#include <cstdlib>

namespace {
void* volatile last_block = nullptr;
}

int main() {
  last_block = std::malloc(64);
  last_block = nullptr;
  return 0;
}
