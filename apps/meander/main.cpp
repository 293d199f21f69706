#include <cstdio>
int main() { std::puts("meander: not yet"); return 0; }
