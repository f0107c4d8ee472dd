// The program that carries the test programs' precompiled header (cmake/RescuesimPch.cmake):
// built, never run.
int main() { return 0; }
