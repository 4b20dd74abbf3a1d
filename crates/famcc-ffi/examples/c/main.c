/*
 * famcc C ABI example: the paper's example 1 (order 2, float) on the authors'
 * second-order plant (disturbance amplitude 3), closed loop at 1 kHz.
 *
 * Host:       gcc -std=c11 -Wall -Wextra -Werror -I../../include main.c \
 *                 libfamcc_ffi.a -lm -o famcc-example
 * Cortex-M4F: arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -mfloat-abi=hard
 *                 -mfpu=fpv4-sp-d16 ... main.c cortex-m/startup.c
 *                 <thumbv7em-none-eabihf>/libfamcc_ffi.a  (see
 *                 scripts/firmware-check.sh; runs under QEMU mps2-an386)
 *
 * Prints the first steps, then a closed-loop summary, runs the same loop with
 * the extended observer (beyond the paper), and exercises the error paths. Exit status 0 when every check holds.
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "famcc.h"

static int failures = 0;

static void check(int ok, const char *what)
{
    if (!ok) {
        printf("FAIL: %s\n", what);
        failures++;
    }
}

/* Example 1: LaMC, finite-time law k = 1, p = 0.5, eps_x = 0.1, T_s = 1 s,
 * k_u = 5, high-gain differentiator mu = 0.01, a = (4, 4), authors' latch. */
static void example1(FamccConfigF32 *cfg)
{
    famcc_config_f32_defaults(cfg);
    cfg->dt = 1e-3f;
    cfg->settle_time = 1.0f;
    cfg->k_u = 5.0f;
    cfg->constraint.kind = FAMCC_CONSTRAINT_KIND_LATERAL;
    cfg->constraint.eps_x = 0.1f;
    cfg->latch = FAMCC_LATCH_AUTHORS;
    cfg->stages[0].feedback.kind = FAMCC_FEEDBACK_KIND_FINITE_TIME;
    cfg->stages[0].feedback.params.finite_time.k = 1.0f;
    cfg->stages[0].feedback.params.finite_time.p = 0.5f;
    cfg->stages[0].skew.kind = FAMCC_SKEW_KIND_NONE;
    cfg->differentiator.enabled = 1;
    cfg->differentiator.mu = 0.01f;
    cfg->differentiator.a[0] = 4.0f;
    cfg->differentiator.a[1] = 4.0f;
    cfg->differentiator.discretization = FAMCC_DISCRETIZATION_EXACT;
}

/* The authors' plant of examples 1/2: x1' = (1 + 0.1 cos x1 + 0.1 sin t) x2 - x1 + sin t,
 * x2' = (2 + 0.2 sin(x1 x2) + 0.1 cos t) u - (x1^2 - 1) x2 + 3 (sin t + cos 2t). */
static void plant(float t, const float x[2], float u, float dx[2])
{
    dx[0] = (1.0f + 0.1f * cosf(x[0]) + 0.1f * sinf(t)) * x[1] - x[0] + sinf(t);
    dx[1] = (2.0f + 0.2f * sinf(x[0] * x[1]) + 0.1f * cosf(t)) * u - (x[0] * x[0] - 1.0f) * x[1]
            + 3.0f * (sinf(t) + cosf(2.0f * t));
}

static void rk4(float t, float x[2], float u, float h)
{
    float k1[2], k2[2], k3[2], k4[2], y[2];
    plant(t, x, u, k1);
    for (int i = 0; i < 2; i++) y[i] = x[i] + 0.5f * h * k1[i];
    plant(t + 0.5f * h, y, u, k2);
    for (int i = 0; i < 2; i++) y[i] = x[i] + 0.5f * h * k2[i];
    plant(t + 0.5f * h, y, u, k3);
    for (int i = 0; i < 2; i++) y[i] = x[i] + h * k3[i];
    plant(t + h, y, u, k4);
    for (int i = 0; i < 2; i++) x[i] += h / 6.0f * (k1[i] + 2.0f * k2[i] + 2.0f * k3[i] + k4[i]);
}

/* Storage for the controller: a plain static object, no allocation. */
static FamccO2F32 ctrl;

/* Example 1 with the extended observer in the differentiator's place (beyond
 * the paper): it estimates the plant's unknown term from the error and the
 * applied input, and the law cancels it, bounded by 20. */
static int observed(FamccConfigF32 *cfg)
{
    example1(cfg);
    cfg->differentiator.enabled = 0;
    if (famcc_observer_f32_binomial(2, 0.02f, 2.0f, &cfg->observer) != FAMCC_STATUS_OK) return 0;
    cfg->observer.has_cancellation_limit = 1;
    cfg->observer.cancellation_limit = 20.0f;
    cfg->has_output_limits = 1;
    cfg->output_limits[0] = -100.0f;
    cfg->output_limits[1] = 100.0f;
    return 1;
}

/* The closed loop at 1 kHz for 5 s from x = (-1, 0.5), tracking sin t, with u
 * limited to +-100 and the applied input reported back. Returns 0 on a failed
 * call; else writes when |z1| < 0.1 from on, max |xi~|, u's range and the
 * largest |z1| over the last second. */
static int run(const FamccConfigF32 *cfg, int print, float *settled, float *max_xi, float u_range[2],
               float *late)
{
    FamccError err;
    FamccStatus st = famcc_o2_f32_init(&ctrl, cfg, &err);
    if (st != FAMCC_STATUS_OK) {
        printf("init failed: %s: stage %d %s %s\n", famcc_status_str(st), (int)err.stage, err.parameter,
               err.rule);
        return 0;
    }
    const float dt = cfg->dt;
    const int steps = 5001; /* 5 s */
    const int substeps = 4;
    float x[2] = {-1.0f, 0.5f}, applied = 0.0f;
    int last_out = -1;
    *max_xi = 0.0f;
    *late = 0.0f;
    u_range[0] = 1e30f;
    u_range[1] = -1e30f;
    if (print) printf("   k      t        e           v          xi~\n");
    for (int k = 0; k < steps; k++) {
        float t = (float)k * dt;
        float e = x[0] - sinf(t);
        float v;
        st = k == 0 ? famcc_o2_f32_step(&ctrl, e, &v) : famcc_o2_f32_step_applied(&ctrl, e, applied, &v);
        if (st != FAMCC_STATUS_OK) {
            printf("step %d failed: %s\n", k, famcc_status_str(st));
            return 0;
        }
        FamccDiagnosticsF32 d;
        famcc_o2_f32_diagnostics(&ctrl, &d);
        if (fabsf(d.xi) > *max_xi) *max_xi = fabsf(d.xi);
        if (fabsf(e) >= 0.1f) last_out = k;
        if (k >= steps - 1000 && fabsf(e) > *late) *late = fabsf(e);
        float u = v; /* limits +-100: never reached here after the start */
        if (u > 100.0f) u = 100.0f;
        if (u < -100.0f) u = -100.0f;
        applied = u;
        if (u < u_range[0]) u_range[0] = u;
        if (u > u_range[1]) u_range[1] = u;
        if (print && (k < 5 || k % 500 == 0))
            printf("%5d %6.3f %+10.6f %+11.5f %+10.6f\n", k, (double)t, (double)e, (double)v, (double)d.xi);
        for (int j = 0; j < substeps; j++) rk4(t + (float)j * dt / substeps, x, u, dt / substeps);
    }
    *settled = (float)(last_out + 1) * dt;
    return 1;
}

int main(void)
{
    printf("famcc C example: example 1, order 2, float\n");
    check(sizeof(FamccO2F32) == famcc_o2_f32_size(), "sizeof(FamccO2F32) matches the library");
    check(_Alignof(FamccO2F32) == famcc_o2_f32_align(), "alignment of FamccO2F32 matches the library");

    FamccConfigF32 cfg;
    FamccError err;
    FamccStatus st;
    example1(&cfg);
    float settled, max_xi, u_range[2], late;
    if (!run(&cfg, 1, &settled, &max_xi, u_range, &late)) return 1;
    printf("closed loop: |z1| < 0.1 from t = %.3f s (bound 3 s), max |xi~| = %.6f, u in [%.3f, %.3f]\n",
           (double)settled, (double)max_xi, (double)u_range[0], (double)u_range[1]);
    check(max_xi < 1.0f, "|xi~| < 1 at every sample");
    check(settled <= 3.0f, "|z1| < 0.1 from the theoretical bound (3 s) on");

    /* The same loop with the observer: the same guarantees, a smaller steady error. */
    FamccConfigF32 obs;
    check(observed(&obs), "the observer's default coefficients");
    float settled_o, max_xi_o, u_range_o[2], late_o;
    if (!run(&obs, 0, &settled_o, &max_xi_o, u_range_o, &late_o)) return 1;
    printf("with the observer: |z1| < 0.1 from t = %.3f s, max |xi~| = %.6f; max |z1| over the last "
           "second %.5f (without: %.5f)\n",
           (double)settled_o, (double)max_xi_o, (double)late_o, (double)late);
    check(max_xi_o < 1.0f && settled_o <= 3.0f, "the observer keeps the envelope and the settling bound");
    check(late_o < 0.5f * late, "the observer shrinks the steady error");
    FamccConfigF32 both = obs;
    both.differentiator.enabled = 1;
    st = famcc_o2_f32_init(&ctrl, &both, &err);
    check(st == FAMCC_STATUS_INVALID_CONFIG && strcmp(err.parameter, "differentiator") == 0,
          "an observer and a differentiator together are rejected, naming the differentiator");
    check(famcc_o2_f32_init(&ctrl, &cfg, &err) == FAMCC_STATUS_OK, "re-init the plain design");

    /* Error paths: status codes, never a crash or an unwind. */
    float v = 42.0f;
    check(famcc_o2_f32_step(&ctrl, NAN, &v) == FAMCC_STATUS_NON_FINITE_INPUT && v == 42.0f,
          "NaN input is rejected and v is untouched");
    FamccConfigF32 bad = cfg;
    bad.k_u = -1.0f;
    st = famcc_o2_f32_init(&ctrl, &bad, &err);
    printf("invalid config -> %s: %s %s\n", famcc_status_str(st), err.parameter, err.rule);
    check(st == FAMCC_STATUS_INVALID_CONFIG && strcmp(err.parameter, "k_u") == 0, "k_u < 0 is rejected");
    check(famcc_o2_f32_step(&ctrl, 0.0f, &v) == FAMCC_STATUS_NOT_INITIALIZED,
          "a failed init leaves the storage unusable");
    check(famcc_o2_f32_reset(NULL) == FAMCC_STATUS_NULL_POINTER, "NULL is rejected");

    /* reset: the same first output again. */
    check(famcc_o2_f32_init(&ctrl, &cfg, NULL) == FAMCC_STATUS_OK, "re-init");
    float v1, v2;
    famcc_o2_f32_step(&ctrl, -1.0f, &v1);
    famcc_o2_f32_reset(&ctrl);
    famcc_o2_f32_step(&ctrl, -1.0f, &v2);
    check(v1 == v2, "reset restores the initial state");

    /* The double / order-3 API has the same shape. */
    static FamccO3F64 ctrl3;
    FamccConfigF64 c3;
    famcc_config_f64_defaults(&c3);
    c3.dt = 1e-3;
    c3.k_u = 30.0;
    c3.constraint.kind = FAMCC_CONSTRAINT_KIND_LONGITUDINAL;
    c3.constraint.eps_y = 3.0;
    c3.latch = FAMCC_LATCH_AUTHORS;
    for (int i = 0; i < 2; i++) {
        c3.stages[i].feedback.kind = FAMCC_FEEDBACK_KIND_FIXED_TIME;
        c3.stages[i].feedback.params.fixed_time.alpha = i == 0 ? 1.0 : 2.0;
        c3.stages[i].feedback.params.fixed_time.p = 0.5;
        c3.stages[i].feedback.params.fixed_time.beta = i == 0 ? 0.5 : 1.0;
        c3.stages[i].feedback.params.fixed_time.q = 2.0;
        c3.stages[i].skew.kind = FAMCC_SKEW_KIND_NONSINGULAR;
        c3.stages[i].skew.eps_s = i == 0 ? 0.1 : 3.0;
        c3.stages[i].skew.eps_z = i == 0 ? 0.1 : 0.2;
        c3.stages[i].skew.k_pp = i == 0 ? 0.1 : 1.0;
        c3.stages[i].skew.transition = FAMCC_TRANSITION_EXPONENTIAL;
    }
    c3.differentiator.enabled = 1;
    c3.differentiator.mu = 0.01;
    c3.differentiator.a[0] = 4.0;
    c3.differentiator.a[1] = 6.0;
    c3.differentiator.a[2] = 4.0;
    st = famcc_o3_f64_init(&ctrl3, &c3, &err);
    check(st == FAMCC_STATUS_OK, "example 3 (order 3, double) initialises");
    double v3 = 0.0;
    check(famcc_o3_f64_step(&ctrl3, -0.5, &v3) == FAMCC_STATUS_OK && isfinite(v3), "order-3 step");
    printf("example 3 (order 3, double): first output v = %+.6f\n", v3);

    printf("result: %d failure(s)\n", failures);
    return failures == 0 ? 0 : 1;
}
