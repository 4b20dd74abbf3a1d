/*
 * famcc C ABI checks (issue 15): the storage checks every call makes, from C.
 * NULL, misaligned and undersized storage, the wrong controller type, the
 * observer's defaults and checks, and the status texts. Built and run on the host by scripts/firmware-check.sh:
 *   gcc -std=c11 -Wall -Wextra -Werror -I../../include abi_checks.c libfamcc_ffi.a -lm
 * Exit status: the number of failed checks.
 */
#include <math.h>
#include <stdalign.h>
#include <stdio.h>
#include <string.h>

#include "famcc.h"

static int failures = 0;

#define CHECK(cond)                                                   \
    do {                                                              \
        if (!(cond)) {                                                \
            printf("FAIL %s:%d: %s\n", __FILE__, __LINE__, #cond);    \
            failures++;                                               \
        }                                                             \
    } while (0)

static void config(FamccConfigF32 *cfg)
{
    famcc_config_f32_defaults(cfg);
    cfg->dt = 1e-3f;
    cfg->k_u = 5.0f;
    cfg->constraint.kind = FAMCC_CONSTRAINT_KIND_LATERAL;
    cfg->constraint.eps_x = 0.1f;
    cfg->stages[0].feedback.kind = FAMCC_FEEDBACK_KIND_LINEAR;
    cfg->stages[0].feedback.params.linear.k = 1.0f;
    cfg->differentiator.enabled = 1;
    cfg->differentiator.mu = 0.01f;
    cfg->differentiator.a[0] = 4.0f;
    cfg->differentiator.a[1] = 4.0f;
}

int main(void)
{
    FamccConfigF32 cfg;
    config(&cfg);
    FamccError err;
    float v = 0.0f;

    /* NULL storage, config or output */
    static FamccO2F32 ctrl;
    CHECK(famcc_o2_f32_init(NULL, &cfg, &err) == FAMCC_STATUS_NULL_POINTER);
    CHECK(famcc_o2_f32_init(&ctrl, NULL, &err) == FAMCC_STATUS_NULL_POINTER);
    CHECK(famcc_o2_f32_init_sized(NULL, sizeof ctrl, &cfg, &err) == FAMCC_STATUS_NULL_POINTER);
    CHECK(famcc_o2_f32_step(NULL, 0.1f, &v) == FAMCC_STATUS_NULL_POINTER);
    CHECK(famcc_o2_f32_init(&ctrl, &cfg, &err) == FAMCC_STATUS_OK);
    CHECK(famcc_o2_f32_step(&ctrl, 0.1f, NULL) == FAMCC_STATUS_NULL_POINTER);
    CHECK(famcc_o2_f32_diagnostics(&ctrl, NULL) == FAMCC_STATUS_NULL_POINTER);

    /* a pool buffer: undersized, misaligned, then right */
    static alignas(8) unsigned char pool[sizeof(FamccO2F32) + 16];
    FamccO2F32 *p = (FamccO2F32 *)(void *)pool;
    CHECK(famcc_o2_f32_size() == sizeof(FamccO2F32));
    CHECK(famcc_o2_f32_init_sized(p, famcc_o2_f32_size() - 1, &cfg, &err) ==
          FAMCC_STATUS_STORAGE_TOO_SMALL);
    CHECK(famcc_o2_f32_init_sized(p, 0, &cfg, &err) == FAMCC_STATUS_STORAGE_TOO_SMALL);
    CHECK(famcc_o2_f32_step(p, 0.1f, &v) == FAMCC_STATUS_NOT_INITIALIZED); /* nothing written */
    FamccO2F32 *odd = (FamccO2F32 *)(void *)(pool + 4);
    CHECK(famcc_o2_f32_init_sized(odd, sizeof(FamccO2F32), &cfg, &err) == FAMCC_STATUS_MISALIGNED);
    CHECK(famcc_o2_f32_step(odd, 0.1f, &v) == FAMCC_STATUS_MISALIGNED);
    CHECK(famcc_o2_f32_init_sized(p, sizeof pool, &cfg, &err) == FAMCC_STATUS_OK);
    CHECK(famcc_o2_f32_step(p, 0.1f, &v) == FAMCC_STATUS_OK);

    /* the wrong object type: an order-2 float controller read as others */
    double w = 0.0;
    CHECK(famcc_o3_f32_step((FamccO3F32 *)(void *)p, 0.1f, &v) == FAMCC_STATUS_NOT_INITIALIZED);
    CHECK(famcc_o2_f64_step((FamccO2F64 *)(void *)p, 0.1, &w) == FAMCC_STATUS_NOT_INITIALIZED);
    CHECK(famcc_o3_f64_reset((FamccO3F64 *)(void *)p) == FAMCC_STATUS_NOT_INITIALIZED);
    /* never initialised */
    static FamccO2F32 zeroed;
    CHECK(famcc_o2_f32_step(&zeroed, 0.1f, &v) == FAMCC_STATUS_NOT_INITIALIZED);

    /* an outlier is consumed (OVERFLOW), the next sample steps again */
    CHECK(famcc_o2_f32_step(p, 3.0e38f, &v) == FAMCC_STATUS_OVERFLOW);
    CHECK(famcc_o2_f32_step(p, 0.1f, &v) == FAMCC_STATUS_OK);
    FamccDiagnosticsF32 d;
    CHECK(famcc_o2_f32_diagnostics(p, &d) == FAMCC_STATUS_OK);
    CHECK(d.t == 2.0 * (double)1e-3f); /* the third sample's time is 2 dt */

    /* the recursion precomputed (host) and used (target): the same outputs */
    FamccDiscretizedF32 rec;
    CHECK(famcc_o2_f32_discretize(&cfg, &rec, &err) == FAMCC_STATUS_OK);
    static FamccO2F32 direct, precomputed;
    CHECK(famcc_o2_f32_init(&direct, &cfg, &err) == FAMCC_STATUS_OK);
    CHECK(famcc_o2_f32_init_discretized(&precomputed, &cfg, &rec, &err) == FAMCC_STATUS_OK);
    for (int k = 0; k < 100; k++) {
        float e = 0.5f - 0.01f * (float)k, a = 0.0f, b = 1.0f;
        CHECK(famcc_o2_f32_step(&direct, e, &a) == FAMCC_STATUS_OK);
        CHECK(famcc_o2_f32_step(&precomputed, e, &b) == FAMCC_STATUS_OK);
        CHECK(memcmp(&a, &b, sizeof a) == 0);
    }
    rec.phi[1][1] = 1.5f; /* unstable: rejected, naming the parameter */
    CHECK(famcc_o2_f32_init_discretized(&precomputed, &cfg, &rec, &err) ==
          FAMCC_STATUS_INVALID_CONFIG);
    CHECK(strcmp(err.parameter, "discretized") == 0);
    CHECK(famcc_o2_f32_init_discretized(&precomputed, &cfg, NULL, &err) == FAMCC_STATUS_NULL_POINTER);

    /* the observer: default coefficients, an order out of range, a bad b0 named */
    FamccConfigF32 ocfg = cfg;
    ocfg.differentiator.enabled = 0;
    CHECK(famcc_observer_f32_binomial(2, 0.02f, 2.0f, &ocfg.observer) == FAMCC_STATUS_OK);
    CHECK(ocfg.observer.enabled == 1 && ocfg.observer.a[2] == 8.0f); /* (s + 2)^3 */
    CHECK(famcc_observer_f32_binomial(0, 0.02f, 2.0f, &ocfg.observer) == FAMCC_STATUS_INVALID_CONFIG);
    CHECK(famcc_observer_f32_binomial(7, 0.02f, 2.0f, &ocfg.observer) == FAMCC_STATUS_INVALID_CONFIG);
    CHECK(famcc_observer_f32_binomial(2, 0.02f, 2.0f, NULL) == FAMCC_STATUS_NULL_POINTER);
    CHECK(famcc_o2_f32_init(&direct, &ocfg, &err) == FAMCC_STATUS_INVALID_CONFIG); /* no limits */
    CHECK(strcmp(err.parameter, "cancellation_limit") == 0);
    ocfg.has_output_limits = 1;
    ocfg.output_limits[0] = -8.0f;
    ocfg.output_limits[1] = 8.0f;
    CHECK(famcc_o2_f32_init(&direct, &ocfg, &err) == FAMCC_STATUS_OK);
    for (int k = 0; k < 100; k++) {
        CHECK(famcc_o2_f32_step_applied(&direct, 0.2f, k == 0 ? 0.0f : v, &v) == FAMCC_STATUS_OK);
    }
    CHECK(famcc_o2_f32_diagnostics(&direct, &d) == FAMCC_STATUS_OK);
    CHECK(d.lumped != 0.0f && d.cancellation != 0.0f && fabsf(d.cancellation) <= 8.0f); /* delta: half the range */
    ocfg.observer.b0 = -2.0f; /* a negative gain needs the negative direction */
    CHECK(famcc_o2_f32_init(&direct, &ocfg, &err) == FAMCC_STATUS_INVALID_CONFIG);
    CHECK(strcmp(err.parameter, "b0") == 0);
    ocfg.direction = FAMCC_DIRECTION_NEGATIVE;
    CHECK(famcc_o2_f32_init(&direct, &ocfg, &err) == FAMCC_STATUS_OK);
    ocfg.observer.b0 = 0.0f;
    CHECK(famcc_o2_f32_init(&direct, &ocfg, &err) == FAMCC_STATUS_INVALID_CONFIG);
    CHECK(strcmp(err.parameter, "b0") == 0);

    /* the control direction: the default is the paper's; a negative one mirrors the output */
    FamccConfigF32 neg = cfg;
    CHECK(neg.direction == FAMCC_DIRECTION_POSITIVE);
    neg.direction = FAMCC_DIRECTION_NEGATIVE;
    FamccO2F32 pos_c, neg_c;
    CHECK(famcc_o2_f32_init(&pos_c, &cfg, &err) == FAMCC_STATUS_OK);
    CHECK(famcc_o2_f32_init(&neg_c, &neg, &err) == FAMCC_STATUS_OK);
    for (int k = 0; k < 50; k++) {
        float a = 0.0f, b = 0.0f, e = 0.3f * cosf(0.1f * (float)k);
        CHECK(famcc_o2_f32_step(&pos_c, e, &a) == FAMCC_STATUS_OK);
        CHECK(famcc_o2_f32_step(&neg_c, e, &b) == FAMCC_STATUS_OK);
        CHECK(a == -b);
    }
    neg.direction = 2;
    CHECK(famcc_o2_f32_init(&neg_c, &neg, &err) == FAMCC_STATUS_INVALID_CONFIG);
    CHECK(strcmp(err.parameter, "direction") == 0);

    /* every status has a text; OVERFLOW says the sample was consumed */
    for (uint32_t s = 0; s <= FAMCC_STATUS_STORAGE_TOO_SMALL; s++) {
        CHECK(strcmp(famcc_status_str(s), "unknown status") != 0);
    }
    CHECK(strstr(famcc_status_str(FAMCC_STATUS_OVERFLOW), "consumed") != NULL);
    CHECK(strcmp(famcc_status_str(99), "unknown status") == 0);

    printf("C ABI checks: %s (%d failed)\n", failures ? "FAIL" : "ok", failures);
    return failures;
}
