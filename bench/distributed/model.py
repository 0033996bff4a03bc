# The cluster model of docs/distributed.md: a 3840x2160 x 1000-frame render on 16 and 64 nodes,
# from per-core costs measured with bench/distributed/run.sh's render on 2 ranks of 1 thread
# (--stats: stage_seconds and exchanged_bytes.photon_grid_seconds of rank 0).
px = 3840 * 2160
frames = 1000
# measured (192x192, 200k photons/pass, 24 passes, one core per rank, 2 ranks):
cam_per_px = 7.5 / 24 / (192 * 192)      # s per pixel per pass per core (camera pass + gather)
trace_per_ph = 10.8 / 24 / 200000        # s per photon path per core
rec_per_ph = 1.96                         # records per photon path (Cornell box, 8 bounces)
# s per record per core, replicated on every rank: 1.39 s measured, times 0.81 since the sort
# reads its records in order (its CPU samples, relative to the gather's, in one process on one thread)
sort_per_rec = 1.39 * 0.81 / 24 / (rec_per_ph * 200000)
cores = 32
print(f"cam {cam_per_px*1e6:.2f} us/px, trace {trace_per_ph*1e6:.2f} us/photon, sort {sort_per_rec*1e9:.0f} ns/record")
for P in (500_000, 1_000_000):
    rec = rec_per_ph * P
    map_bytes = rec * 40
    t1 = (px * cam_per_px + P * trace_per_ph + rec * sort_per_rec) / cores
    print(f"\nP = {P:,} photons/pass: records {rec/1e6:.2f} M, photon map {map_bytes/1e6:.1f} MB; one node {t1*1e3:.0f} ms/pass")
    for N in (16, 64):
        recv = map_bytes * (N - 1) / N
        divided = (px * cam_per_px + P * trace_per_ph) / (N * cores)
        camera = px * cam_per_px / (N * cores)
        rep = rec * sort_per_rec / cores  # sorting the whole map (received records are sorted in place)
        for gbit in (10, 100):
            comm = recv / (gbit * 1e9 / 8)
            exposed = max(0.0, comm - camera)  # the exchange runs beside the camera pass
            tn = divided + rep + exposed
            eff = t1 / (N * tn)
            print(f"  N={N:2d} {gbit:3d} Gbit/s: receives {recv/1e6:.1f} MB/pass, comm {comm*1e3:.1f} ms "
                  f"(camera pass {camera*1e3:.1f} ms, exposed {exposed*1e3:.1f}), replicated {rep*1e3:.1f} ms, "
                  f"pass {tn*1e3:.1f} ms, efficiency {eff:.2f}")
frame = px * 12
for N in (16, 64):
    for gbit in (10, 100):
        print(f"frames N={N} {gbit} Gbit/s: rank 0 receives {frame*(N-1)/N/1e6:.1f} MB/frame, "
              f"{frames*frame*(N-1)/N/(gbit*1e9/8):.0f} s for {frames} frames")
