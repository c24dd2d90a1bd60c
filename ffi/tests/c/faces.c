/* The estimator's loop through the C interface, for the cross-face test
 * (python/tests/test_faces.py): the same log through the `estimate` tool, Python's
 * gyrostat.estimate and this program must give the same rows, bit for bit.
 *
 *   faces f64|f32 [skip] [rate_rule=trapezoid|magnus4|cf4] < LOG.csv
 *
 * The estimator has the library's default parameters (gyro_estimator_*_default_params), with
 * `rate_rule=NAME` the rule of that name (the `estimate` tool's `--set rate_rule=NAME`,
 * Python's `rate_rule=`); an unknown name is a usage error (exit status 2).
 *
 * LOG.csv: a header line, then rows `t,gx,gy,gz,ax,ay,az[,mx,my,mz]` (s, rad/s, m/s^2, any
 * field unit); three empty magnetometer fields: no field sample in that row. The loop is the
 * one of gyrostat-pipeline (pipeline/src/estimate.rs), written with the C interface:
 *   1. a non-finite time stamp or gyroscope value is a bad row: with `skip` the row repeats the
 *      state with the flags `skipped` (the clock keeps the last good time stamp: the next good
 *      row propagates over the whole interval), without it the run stops;
 *   2. the step from the sample clock (gyro_sample_clock_f64, nominal 1000 s, gap factor 1):
 *      the first time stamp has none (NaN, the estimator's first-sample rule), a gap (a step
 *      over 1000 s), a repeated or a backwards time stamp stops the run;
 *   3. the estimator's update (f64, or f32 with every input and the step rounded to float); a
 *      gyroscope value that is not finite in f32 is a bad row as in 1.
 * Output (stdout): `t,qw,qx,qy,qz,bx,by,bz,rest,gyro,accel,mag` per row (t as written, the
 * numbers with %.17g (f64) or %.9g (f32), which round-trip; `nan` before the attitude is
 * initialised), the estimate tool's columns without its heading flag. A row that stops the
 * run: `error: line N: status S` on stderr, exit status 1. */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gyrostat.h"

#define MAX_LINE 4096
#define MAX_FIELDS 16

static const char *use_name(uint32_t u) {
  switch (u) {
    case GYRO_SENSOR_USED: return "used";
    case GYRO_SENSOR_ABSENT: return "absent";
    case GYRO_SENSOR_NON_FINITE: return "nonfinite";
    case GYRO_SENSOR_SATURATED: return "saturated";
    case GYRO_SENSOR_DISTURBED: return "disturbed";
    case GYRO_SENSOR_ZERO: return "zero";
    default: return "?";
  }
}

/* Splits `line` at commas in place (the line end removed); returns the number of fields. */
static int split(char *line, char **fields) {
  int n = 0;
  line[strcspn(line, "\r\n")] = 0;
  char *p = line;
  for (;;) {
    if (n == MAX_FIELDS) return -1;
    fields[n++] = p;
    char *c = strchr(p, ',');
    if (!c) break;
    *c = 0;
    p = c + 1;
  }
  return n;
}

static int number(const char *s, double *out) {
  char *end;
  if (*s == 0) return 0;
  *out = strtod(s, &end);
  return *end == 0;
}

typedef struct {
  int f32;
  gyro_estimator_f64 e64;
  gyro_estimator_f32 e32;
} filter;

static void print_row(const filter *f, const char *t, int initialized, const char *flags) {
  if (!initialized) {
    printf("%s,nan,nan,nan,nan,nan,nan,nan,%s\n", t, flags);
  } else if (f->f32) {
    gyro_quat_f32 q;
    gyro_vec3_f32 b;
    gyro_estimator_f32_attitude(&f->e32, &q, &b);
    printf("%s,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%s\n", t, q.w, q.x, q.y, q.z, b.x, b.y, b.z,
           flags);
  } else {
    gyro_quat_f64 q;
    gyro_vec3_f64 b;
    gyro_estimator_f64_attitude(&f->e64, &q, &b);
    printf("%s,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%s\n", t, q.w, q.x, q.y, q.z, b.x, b.y,
           b.z, flags);
  }
}

static int fail(long line, int status) {
  fprintf(stderr, "error: line %ld: status %d\n", line, status);
  return 1;
}

/* The GYRO_RATE_RULE_* code of a rule's name, or -1. */
static long rate_rule(const char *name) {
  if (!strcmp(name, "trapezoid")) return GYRO_RATE_RULE_TRAPEZOID;
  if (!strcmp(name, "magnus4")) return GYRO_RATE_RULE_MAGNUS4;
  if (!strcmp(name, "cf4")) return GYRO_RATE_RULE_CF4;
  return -1;
}

static int usage(void) {
  fprintf(stderr, "usage: faces f64|f32 [skip] [rate_rule=trapezoid|magnus4|cf4] < LOG.csv\n");
  return 2;
}

int main(int argc, char **argv) {
  if (argc < 2 || (strcmp(argv[1], "f64") && strcmp(argv[1], "f32"))) return usage();
  static filter f;
  f.f32 = strcmp(argv[1], "f32") == 0;
  int skip = 0;
  long rule = GYRO_RATE_RULE_DEFAULT;
  for (int i = 2; i < argc; i++) {
    if (!strcmp(argv[i], "skip")) {
      skip = 1;
    } else if (!strncmp(argv[i], "rate_rule=", 10)) {
      rule = rate_rule(argv[i] + 10);
      if (rule < 0) return usage();
    } else {
      return usage();
    }
  }
  gyro_estimator_params_f64 p64;
  gyro_estimator_params_f32 p32;
  if (gyro_estimator_f64_default_params(&p64) || gyro_estimator_f32_default_params(&p32)) return 3;
  p64.rate_rule = p32.rate_rule = (uint32_t)rule;
  if (f.f32 ? gyro_estimator_f32_init_params(&f.e32, &p32)
            : gyro_estimator_f64_init_params(&f.e64, &p64)) {
    return 3;
  }
  gyro_sample_clock_f64 clock;
  if (gyro_sample_clock_f64_init(&clock, 1000.0, 1.0) != GYRO_OK) return 3;

  static char line[MAX_LINE];
  char *fields[MAX_FIELDS];
  long n = 0;
  int initialized = 0;
  if (!fgets(line, sizeof line, stdin)) return 3;
  n++;
  int columns = split(line, fields);
  if (columns != 7 && columns != 10) return 3;
  printf("t,qw,qx,qy,qz,bx,by,bz,rest,gyro,accel,mag\n");
  while (fgets(line, sizeof line, stdin)) {
    n++;
    if (strspn(line, " \t\r\n") == strlen(line)) continue;
    if (split(line, fields) != columns) return fail(n, -1);
    double t, v[9];
    if (!number(fields[0], &t)) return fail(n, -1);
    int has_mag = columns == 10 && !(*fields[7] == 0 && *fields[8] == 0 && *fields[9] == 0);
    for (int i = 0; i < (has_mag ? 9 : 6); i++) {
      if (!number(fields[i + 1], &v[i])) return fail(n, -1);
    }
    const char *skipped = "0,skipped,skipped,skipped";
    /* 1. A bad row. */
    if (!isfinite(t) || !isfinite(v[0]) || !isfinite(v[1]) || !isfinite(v[2])) {
      if (!skip) return fail(n, GYRO_NON_FINITE);
      print_row(&f, fields[0], initialized, skipped);
      continue;
    }
    /* 2. The step. */
    gyro_sample_clock_f64 before = clock;
    uint32_t kind;
    double dt;
    int s = gyro_sample_clock_f64_interval(&clock, t, &kind, &dt);
    if (s != GYRO_OK) return fail(n, s);
    if (kind != GYRO_INTERVAL_FIRST && kind != GYRO_INTERVAL_STEP) return fail(n, -2);
    /* 3. The update. */
    gyro_estimator_outcome o;
    if (f.f32) {
      gyro_vec3_f32 g = {(float)v[0], (float)v[1], (float)v[2]};
      gyro_vec3_f32 a = {(float)v[3], (float)v[4], (float)v[5]};
      gyro_vec3_f32 m = {(float)v[6], (float)v[7], (float)v[8]};
      s = gyro_estimator_f32_update(&f.e32, &g, &a, has_mag ? &m : NULL, (float)dt, &o);
    } else {
      gyro_vec3_f64 g = {v[0], v[1], v[2]};
      gyro_vec3_f64 a = {v[3], v[4], v[5]};
      gyro_vec3_f64 m = {v[6], v[7], v[8]};
      s = gyro_estimator_f64_update(&f.e64, &g, &a, has_mag ? &m : NULL, dt, &o);
    }
    if (s == GYRO_NON_FINITE && skip) {
      clock = before;
      print_row(&f, fields[0], initialized, skipped);
      continue;
    }
    if (s != GYRO_OK) return fail(n, s);
    initialized |= o.initialized != 0;
    char flags[64];
    snprintf(flags, sizeof flags, "%u,%s,%s,%s", o.at_rest, o.gyro_saturated ? "saturated" : "used",
             use_name(o.accel), use_name(o.mag));
    print_row(&f, fields[0], initialized, flags);
  }
  return 0;
}
