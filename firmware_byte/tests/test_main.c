/* test_main.c — runs every suite; exit status 0 only if every check passed. */
#include "tt.h"

int tt_tests, tt_checks, tt_fails;
const char *tt_current = "";
bb_state S;
int RLO;

int main(void) {
  suite_arith();
  suite_compare();
  suite_timers();
  suite_counters();
  suite_exchange();
  suite_serial();
  suite_bus();
  suite_costs();
  suite_program();
  suite_contexts();
  printf("firmware_byte unit tests: %d tests, %d checks, %d failed\n", tt_tests, tt_checks,
         tt_fails);
  return tt_fails == 0 ? 0 : 1;
}
