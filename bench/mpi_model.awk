#!/usr/bin/awk -f
# mpi_model.awk - the farm's cost model (mpi/README.md, "Cost model"),
# fed with the costs bench_mpi.sh measures at 1-2 ranks.  D traces (a
# sweep's designs; D = 1: one curve) of R paths each on N ranks, as
# mpi/farm_set.c schedules them: worker 0 is rank 0's own thread, 1..N-1
# the other ranks; a worker that is free takes a piece of a trace whose
# scene it built (oldest first), else opens the next trace, else joins
# the trace with the most pieces free; a trace's main pieces wait for its guide
# (its pilot's last piece, + g).  A piece of a pass of P paths in nb
# batches, K angle chunks, costs
#   c = c0 + (P / nb) (alpha + beta / K)  [+ m on a remote rank] [+ b: the
#       first piece of a trace on a worker builds its scene]
# c0: a piece's fixed cost (a pass set up).
# K = ceil(f N / (nb D)), f = 2, at most the angles (farm_set.c's
# chunks_for; f = 4 before, kept as an option to compare).
# The pilot: min(R / 10, 200000) paths, 8 batches (when R / 10 >= 1000).
# Then
#   T(N) = S + max(makespan + c_done, rank-0 bound)
# S: rank 0's start (job checks, Ts); c_done: the caller's work on the
# last trace (its curve written, Tc); rank-0 bound: everything rank 0's
# MPI thread does one at a time: D Tc + the remote pieces' bytes / bw +
# h per remote piece.  T(1) = S + makespan(1 worker) + D Tc: one process
# does it all on one core.  Efficiency T(1) / (N T(N)).
# Usage:
#   awk -f mpi_model.awk -v S= -v c0= -v alpha= -v beta= -v m= -v b= -v Tc= \
#       -v bm= -v bp= -v bw= -v h= -v R= -v B=64 -v D=64 -v angles=67 \
#       -v ranks="1 2 16 64 256"
# bm, bp: bytes of a main and a pilot piece of one chunk (all angles);
# a piece of K chunks carries about 1/K of them.
function ceil(x) { return x == int(x) ? x : int(x) + (x > 0) }
function chunks(nb, n,    k) { k = ceil(f * n / (nb * D)); if (k > angles) k = angles;
	return k < 1 ? 1 : k }
# a free piece of trace i at time t: 1 pilot, 2 main, 0 none
function free_piece(i, t) {
	if (pl[i] > 0) return 1;
	if (pilot && pl[i] == 0 && pgiven[i] == np && gready[i] > t) return 0;
	return ml[i] > 0 ? 2 : 0;
}
function makespan(n,    j, i, t, best, pick, kind, c, ms, next_t, most, k2) {
	kp = chunks(8, n); km = chunks(B, n);
	np = pilot ? 8 * kp : 0; nm = B * km;
	cp = c0 + Rp / 8 * (alpha + beta / kp); cm = c0 + R / B * (alpha + beta / km);
	for (i = 0; i < D; i++) { pl[i] = np; pgiven[i] = 0; pend[i] = 0;
		gready[i] = 0; ml[i] = nm }
	delete held; opened = 0; remote = 0; rbytes = 0; builds = 0; idle = 0;
	for (j = 0; j < n; j++) { free_at[j] = j ? bstart : 0; done_w[j] = 0 }
	for (;;) {
		best = -1;
		for (j = 0; j < n; j++)
			if (!done_w[j] && (best < 0 || free_at[j] < free_at[best])) best = j;
		if (best < 0) break;
		j = best; t = free_at[j]; pick = -1; kind = 0;
		for (i = 0; i < opened && pick < 0; i++)
			if (((j, i) in held) && (kind = free_piece(i, t))) pick = i;
		if (pick < 0 && opened < D) { pick = opened++; kind = free_piece(pick, t) }
		if (pick < 0) {	# join the trace with the most pieces free
			most = 0;
			for (i = 0; i < opened; i++)
				if ((k2 = free_piece(i, t)) && (k2 == 1 ? pl[i] : ml[i]) > most) {
					most = k2 == 1 ? pl[i] : ml[i]; pick = i; kind = k2 }
		}
		if (pick < 0 || !kind) {	# wait for the next guide, or stop
			next_t = -1;
			for (i = 0; i < opened; i++)
				if (ml[i] > 0 && gready[i] > t && (next_t < 0 || gready[i] < next_t))
					next_t = gready[i];
			if (next_t < 0) { done_w[j] = 1; continue }
			idle += next_t - t; free_at[j] = next_t; continue;
		}
		c = kind == 1 ? cp : cm;
		if (!((j, pick) in held)) { c += b; held[j, pick] = 1; builds++ }
		if (j) { c += m; remote++; rbytes += kind == 1 ? bp / kp : bm / km }
		free_at[j] = t + c;
		if (kind == 1) {
			pl[pick]--; pgiven[pick]++;
			if (free_at[j] > pend[pick]) pend[pick] = free_at[j];
			if (pgiven[pick] == np) gready[pick] = pend[pick] + g;
		} else ml[pick]--;
	}
	ms = 0; for (j = 0; j < n; j++) if (free_at[j] > ms) ms = free_at[j];
	retrace = D * (R * (km - 1) + Rp * (kp - 1)) * alpha;
	return ms;
}
function total(n,    ms, bound) {
	ms = makespan(n);
	if (n == 1) return S + ms + D * Tc;
	bound = D * Tc + rbytes / bw + remote * h;
	rank0_bound = bound > ms + Tc;
	return S + (rank0_bound ? bound : ms + Tc);
}
BEGIN {
	if (B == "") B = 64; if (angles == "") angles = 127; if (D == "") D = 1;
	if (f == "") f = 2; if (c0 == "") c0 = 0; if (g == "") g = 0.001; if (h == "") h = 2e-5; if (bstart == "") bstart = 0;
	Rp = R / 10 > 200000 ? 200000 : int(R / 10); pilot = R / 10 >= 1000;
	t1 = total(1); work1 = D * (R * (alpha + beta) + (pilot ? Rp * (alpha + beta) : 0));
	printf "%6s %10s %7s %7s %7s  %s\n", "ranks", "time_s", "speedup", "effic",
		"builds", "lost share of N T(N): start+last-curve scene-builds retrace latency idle+tail  limit";
	nr = split(ranks, rk, " ");
	for (k = 1; k <= nr; k++) {
		n = rk[k]; t = total(n); tot = n * t;
		ls = (S + Tc) * (n - 1) / tot;		# others idle while rank 0 starts and ends
		lb = (builds - D) * b / tot;		# scenes built more than once
		lr = retrace * 1.1 / tot;		# paths retraced by angle chunks
		lm = remote * m / tot;			# remote pieces' latency
		li = 1 - t1 / tot - ls - lb - lr - lm;	# waiting for guides, the tail
		lim = "start and the last curve (S + Tc)"; big = ls;
		if (lb > big) { lim = "scene builds (" builds " for " D " traces)"; big = lb }
		if (lr > big) { lim = "angle chunks retracing paths (K = " kp ", " km ")"; big = lr }
		if (lm > big) { lim = "remote-piece latency m"; big = lm }
		if (li > big) { lim = "the tail: last pieces, guides awaited"; big = li }
		if (rank0_bound && n > 1) lim = "rank 0's MPI thread (curves, bytes, messages)";
		printf "%6d %10.4g %7.2f %7.3f %7d  %6.3f %6.3f %6.3f %6.3f %6.3f  limit: %s\n",
			n, t, t1 / t, t1 / tot, builds, ls, lb, lr, lm, li,
			(n > 1 ? lim : "-");
	}
}
