// The per-stage cost budgets (tests/budget/stage_cost.sh, label "budget") count instructions by
// function: stage functions stay out of line so that callgrind sees each as one call.
#pragma once

#define DPCR_STAGE __attribute__((noinline))
