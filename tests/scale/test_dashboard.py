"""optuna-dashboard on a study's storage (issue 17, item 5): the dashboard's WSGI app served on
a loopback port reads the study list and a study's trials back over HTTP."""
import json
import threading
import urllib.request
from wsgiref.simple_server import WSGIRequestHandler, make_server

import optuna
import pytest
from optuna_dashboard import wsgi

HTTP_TIMEOUT = 30  # s, per request; an answer takes milliseconds


class QuietHandler(WSGIRequestHandler):
    def log_message(self, *args):
        pass


def get_json(port, path):
    with urllib.request.urlopen(f"http://127.0.0.1:{port}{path}", timeout=HTTP_TIMEOUT) as response:
        assert response.status == 200
        return json.loads(response.read())


@pytest.mark.parametrize("backend", ["sqlite", "postgresql"])
def test_dashboard_lists_the_study_over_http(backend, request, tmp_path):
    url = f"sqlite:///{tmp_path / 'study.db'}" if backend == "sqlite" else request.getfixturevalue("postgres_url")
    study = optuna.create_study(storage=url, study_name="pinion-verified", direction="minimize")
    for x in (1.0, 2.0, 3.0):
        study.enqueue_trial({"PCR": 40.0 * x})
    study.optimize(lambda t: t.suggest_float("PCR", 20.0, 150.0) ** 2, n_trials=3)
    server = make_server("127.0.0.1", 0, wsgi(optuna.storages.RDBStorage(url)), handler_class=QuietHandler)
    thread = threading.Thread(target=server.serve_forever, daemon=True)
    thread.start()
    try:
        port = server.server_port
        studies = get_json(port, "/api/studies")["study_summaries"]
        assert [s["study_name"] for s in studies] == ["pinion-verified"]
        detail = get_json(port, f"/api/studies/{studies[0]['study_id']}")
        assert sorted(t["values"][0] for t in detail["trials"]) == [1600.0, 6400.0, 14400.0]
    finally:
        server.shutdown()
        server.server_close()
        thread.join(HTTP_TIMEOUT)
