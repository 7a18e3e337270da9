// Over the core's stack budget on purpose (core/CMakeLists.txt): the budget check must reject it.
int SumThroughStack(const int* in, int n) {
  volatile int buffer[512];  // 2 KiB
  int s = 0;
  for (int i = 0; i < n && i < 512; ++i) buffer[i] = in[i];
  for (int i = 0; i < n && i < 512; ++i) s += buffer[i];
  return s;
}
