/* The C test scenario (scenario.c): writes its result lines through `put`. */
#ifndef GYROSTAT_FFI_SCENARIO_H
#define GYROSTAT_FFI_SCENARIO_H
typedef void (*scenario_put_fn)(const char *line);
void scenario_run(scenario_put_fn put);
#endif
