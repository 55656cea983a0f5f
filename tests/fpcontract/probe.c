/* probe.c: prints a*b + c for a = 1 + 2^-30, b = 1 - 2^-30, c = -1.
 * The exact product is 1 - 2^-60, which rounds to 1: evaluated as written
 * (product rounded, then sum) the result is 0; fused into one multiply-add
 * it is -2^-60.  tests/test_fpcontract.c compiles this with the project's
 * flags and checks which one the compiler produced. */
#include <stdio.h>

__attribute__((noinline)) static double muladd(double a, double b, double c)
{
    return a * b + c;
}

int main(void)
{
    volatile double a = 1.0 + 0x1p-30, b = 1.0 - 0x1p-30, c = -1.0;
    printf("%a\n", muladd(a, b, c));
    return 0;
}
