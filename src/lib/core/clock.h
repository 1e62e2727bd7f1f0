/* clock.h - seconds on the clocks that the programs' -v figures and the
 * library's own phase times read. */
#ifndef FCT_CLOCK_H
#define FCT_CLOCK_H

/* Seconds on a monotonic clock. */
double fct_now(void);
/* CPU seconds used by this process. */
double fct_cpu_time(void);

#endif
