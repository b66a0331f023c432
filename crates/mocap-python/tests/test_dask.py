"""The Dask recipe of docs/python.md on a LocalCluster of two worker processes:
its manifest lines equal the local loop's over the corpus."""

from dask import distributed

import mocap
from mocap import motion_files, summarise


def test_dask_local_cluster_matches_the_local_loop(corpus):
    files = motion_files(corpus / "bvh")
    assert len(files) > 20
    local = [summarise(f) for f in files]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as client:
            assert len(client.scheduler_info()["workers"]) == 2
            # The recipe: one task per file, results gathered in file order.
            futures = client.map(summarise, files)
            remote = client.gather(futures)
            # Clips cross process boundaries too (they pickle).
            clip = client.submit(mocap.read, files[0]).result()
    assert remote == local
    assert clip.frame_count == mocap.read(files[0]).frame_count
