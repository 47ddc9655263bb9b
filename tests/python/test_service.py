# SPDX-License-Identifier: AGPL-3.0-or-later
"""Client.health, Client.server_info, connections (TLS, mutual TLS, no
server, closed client)."""
import os
import subprocess

import grpc
import pytest

import dot_client
from conftest import Server, free_port
from shapes import monkey_saddle


def test_health(client):
    assert client.health() == "SERVING"
    assert client.health("dot.v1.Triangulator") == "SERVING"
    with pytest.raises(dot_client.DotError) as e:
        client.health("no.such.Service")
    assert e.value.code == grpc.StatusCode.NOT_FOUND


def test_server_info(client):
    info = client.server_info()
    assert isinstance(info, dot_client.ServerInfo)
    assert info.version
    assert info.license == "AGPL-3.0-or-later"
    assert any("cgal" in b for b in info.backends)
    assert info.limits.compute_threads == 2
    assert info.limits.max_vertices > 0
    assert info.to_dict()["limits"]["queue_size"] == info.limits.queue_size


def test_limits_of_a_limited_server(limited_server):
    with dot_client.Client(limited_server.address) as c:
        assert c.server_info().limits.max_vertices == 100


def test_no_server_is_unavailable():
    with dot_client.Client(f"127.0.0.1:{free_port()}", timeout=10) as c:
        for call in (c.health, c.server_info,
                     lambda: c.triangulate(monkey_saddle(5)),
                     lambda: c.triangulate_many([monkey_saddle(5)]),
                     lambda: c.fill_holes(monkey_saddle(3), [[0, 1, 2]])):
            with pytest.raises(dot_client.DotError) as e:
                call()
            assert e.value.code == grpc.StatusCode.UNAVAILABLE
            assert str(e.value).startswith("UNAVAILABLE: ")


def test_closed_client():
    c = dot_client.Client("127.0.0.1:1")
    with c:
        pass
    with pytest.raises(dot_client.DotError) as e:
        c.health()
    assert e.value.code == grpc.StatusCode.FAILED_PRECONDITION
    with pytest.raises(dot_client.DotError):
        c.triangulate(monkey_saddle(5))


def test_bad_client_arguments(tmp_path):
    with pytest.raises(dot_client.InvalidInput, match="address"):
        dot_client.Client("")
    with pytest.raises(dot_client.InvalidInput, match="go together"):
        dot_client.Client("127.0.0.1:1", tls_cert="a.pem")
    with pytest.raises(dot_client.InvalidInput, match="cannot read tls_ca"):
        dot_client.Client("127.0.0.1:1", tls_ca=str(tmp_path / "none.pem"))
    with pytest.raises(dot_client.InvalidInput, match="timeout"):
        dot_client.Client("127.0.0.1:1", timeout=-1)


@pytest.fixture(scope="module")
def certificates(tmp_path_factory):
    """A CA, a server certificate for 127.0.0.1 and a client certificate."""
    d = tmp_path_factory.mktemp("tls")
    script = (
        "openssl req -x509 -newkey rsa:2048 -nodes -keyout ca.key -out ca.pem"
        " -days 2 -subj /CN=dot-test-ca && "
        "openssl req -newkey rsa:2048 -nodes -keyout server.key -out "
        "server.csr -subj /CN=localhost && "
        "printf 'subjectAltName=DNS:localhost,IP:127.0.0.1' > san.ext && "
        "openssl x509 -req -in server.csr -CA ca.pem -CAkey ca.key "
        "-CAcreateserial -out server.pem -days 2 -extfile san.ext && "
        "openssl req -newkey rsa:2048 -nodes -keyout client.key -out "
        "client.csr -subj /CN=dot-test-client && "
        "openssl x509 -req -in client.csr -CA ca.pem -CAkey ca.key "
        "-CAcreateserial -out client.pem -days 2")
    subprocess.run(["/bin/sh", "-c", script], cwd=d, check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return {name: os.path.join(d, name) for name in
            ("ca.pem", "server.pem", "server.key", "client.pem", "client.key")}


def test_tls_and_mutual_tls(certificates):
    c = certificates
    s = Server("--tls-cert", c["server.pem"], "--tls-key", c["server.key"],
               tls_ca=c["ca.pem"])
    try:
        with dot_client.Client(s.address, tls_ca=c["ca.pem"], timeout=10) as t:
            assert t.triangulate(monkey_saddle(20)).ok
        with dot_client.Client(s.address, timeout=5) as plain:
            with pytest.raises(dot_client.DotError) as e:
                plain.health()
            assert e.value.code == grpc.StatusCode.UNAVAILABLE
    finally:
        s.stop()
    s = Server("--tls-cert", c["server.pem"], "--tls-key", c["server.key"],
               "--tls-client-ca", c["ca.pem"], tls_ca=c["ca.pem"],
               tls_cert=c["client.pem"], tls_key=c["client.key"])
    try:
        with dot_client.Client(s.address, tls_ca=c["ca.pem"],
                               tls_cert=c["client.pem"],
                               tls_key=c["client.key"], timeout=10) as m:
            assert m.health() == "SERVING"
            assert m.triangulate(monkey_saddle(20)).ok
        with dot_client.Client(s.address, tls_ca=c["ca.pem"], timeout=5) as anon:
            with pytest.raises(dot_client.DotError) as e:
                anon.health()
            assert e.value.code == grpc.StatusCode.UNAVAILABLE
    finally:
        s.stop()
