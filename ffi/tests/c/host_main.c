/* The C test scenario on the host: its lines on standard output. */
#include <stdio.h>

#include "scenario.h"

static void put(const char *line) { fputs(line, stdout); }

int main(void) {
  scenario_run(put);
  return 0;
}
