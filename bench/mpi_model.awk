#!/usr/bin/awk -f
# mpi_model.awk - the farm's cost model (mpi/README.md, "Cost model"),
# fed with the costs bench_mpi.sh measures at 1-2 ranks.  For N ranks
# (N workers: rank 0's own thread and ranks 1..N-1) one trace is
#   T(N) = Tser + Ts + pass(pilot) + pass(main)
# Tser: per-command serial work on rank 0 (scene, curve, judging; sweep:
# per design); Ts: the farm's fixed cost (job, guide from the pilot);
# each pass is a list schedule (rank 0 hands pieces to the first free
# rank) of B x K pieces, K = the angle chunks farm_master.c picks
# (ceil(4N / B), at most the angles), one piece costing
#   c = (R / B) (alpha + beta / K) + m
# alpha: tracing one path (every chunk retraces its batch's paths), beta:
# its connections to all angles, m: the extra time of a remote piece on
# its rank (latency), mm in the main pass, mp in the pilot; bm and bp
# their bytes (~4 kB, ~1 MB: the guide's cells): rank 0 receives and
# adds them one at a time at bw bytes/s, so a pass takes at least
# P (N-1)/N bytes / bw.  Ranks 1..N-1 start a trace b later (they build the
# scene from the job).  Usage:
#   awk -f mpi_model.awk -v Tser= -v Ts= -v alpha= -v beta= -v mm= -v mp= -v bm= -v bp= -v bw= -v b= \
#       -v R= -v B=64 -v angles=127 -v D=1 -v ranks="1 2 16 64 256"
function ceil(x) { return x == int(x) ? x : int(x) + (x > 0) }
function chunks(nb, n) { k = ceil(4 * n / nb); if (k > angles) k = angles;
	return k < 1 ? 1 : k }
# one pass: makespan of P equal pieces on n workers, rank 0 at 0,
# the others free at b; also the bound from rank 0's message work
function pass(paths, nb, n, m, by,    k, p, c, i, j, best, t, ms, msg) {
	k = chunks(nb, n); p = nb * k;
	c = paths / nb * (alpha + beta / k);
	for (j = 0; j < n; j++) free_at[j] = j ? b : 0;
	for (i = 0; i < p; i++) {
		best = 0;
		for (j = 1; j < n; j++) if (free_at[j] < free_at[best]) best = j;
		free_at[best] += c + (best ? m : 0);
	}
	ms = 0; for (j = 0; j < n; j++) if (free_at[j] > ms) ms = free_at[j];
	msg = p * (n - 1) / n * by / bw;	# rank 0 receives them one by one
	if (msg > ms) { bytes_loss += msg - ms; ms = msg }
	npieces += p; retrace += paths * alpha * (k - 1);
	return ms;
}
function trace_time(n) {
	npieces = 0; retrace = 0; bytes_loss = 0;
	return Tser + Ts + pass(R / 10, 8, n, mp, bp) + pass(R, B, n, mm, bm);
}
BEGIN {
	if (B == "") B = 64; if (angles == "") angles = 127; if (D == "") D = 1;
	t1 = trace_time(1);
	work = t1 - Tser - Ts;
	printf "%6s %10s %7s %7s  %s\n", "ranks", "time_s", "speedup", "effic",
		"lost share of N T(N): serial retrace rank0-bytes latency+imbalance";
	nr = split(ranks, rk, " ");
	for (i = 1; i <= nr; i++) {
		n = rk[i]; t = trace_time(n);
		ser = (Tser + Ts) * (n - 1);	# core-seconds idle in the serial part
		rt = retrace * 1.1;		# core-seconds of extra path tracing
		tot = n * t; by = bytes_loss * n; rest = tot - t1 - ser - rt - by;
		lim = "serial part (Tser + Ts)"; big = ser;
		if (rt > big) { lim = "angle chunks retracing paths"; big = rt }
		if (by > big) { lim = "rank 0 receiving the pilot's 1 MB pieces"; big = by }
		if (rest > big) lim = "remote-piece latency and piece granularity";
		printf "%6d %10.4g %7.2f %7.3f  %6.3f %6.3f %6.3f %6.3f  limit: %s\n",
			n, D * t, t1 / t, t1 / (n * t), ser / tot, rt / tot,
			by / tot, rest / tot, (n > 1 ? lim : "-");
	}
}
