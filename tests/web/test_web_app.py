"""The web app of `gproj serve` in headless Chromium (Debian's chromium, chromium-driver and
python3-selenium): open an example and run it, read <body data-status> and the shown measure,
fix a vertex by clicking it, drag one and see the re-solve, open a generated mesh file, and
take a screenshot. Results are checked against the API's run and an independent planarity
measure, not only against what the page says.

A run is awaited by its status, with no deadline of its own: a hang fails by ctest's timeout."""

import json
import math
import os
import random
import re
import subprocess
import tempfile
import time
import urllib.request

import pytest
from selenium import webdriver
from selenium.webdriver.chrome.options import Options
from selenium.webdriver.chrome.service import Service
from selenium.webdriver.common.actions.action_builder import ActionBuilder
from selenium.webdriver.common.by import By
from selenium.webdriver.support.ui import Select

BINARY = os.environ["GPROJ_BINARY"]
OUT = os.environ.get("GPROJ_TEST_BUILD_DIR", tempfile.gettempdir())
FINISHED = ("converged", "not-converged", "failed")


@pytest.fixture(scope="module")
def server():
    process = subprocess.Popen([BINARY, "serve", "--port", "0"], stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, text=True)
    line = process.stdout.readline()
    match = re.search(r"listening on http://127\.0\.0\.1:(\d+)/", line)
    assert match, line
    yield f"http://127.0.0.1:{match.group(1)}"
    process.terminate()
    assert process.wait() == 0


@pytest.fixture(scope="module")
def browser():
    options = Options()
    for argument in ("--headless=new", "--no-sandbox", "--disable-dev-shm-usage",
                     "--window-size=1200,800", "--use-angle=swiftshader",
                     "--enable-unsafe-swiftshader"):
        options.add_argument(argument)
    options.set_capability("goog:loggingPrefs", {"browser": "ALL"})
    driver = webdriver.Chrome(service=Service("/usr/bin/chromedriver"), options=options)
    yield driver
    driver.quit()


def api(server, path):
    with urllib.request.urlopen(server + path) as answer:
        return json.loads(answer.read())


def status(browser):
    return browser.find_element(By.TAG_NAME, "body").get_attribute("data-status")


def await_idle(browser):
    """Waits until the page has no run, re-solve or edit in flight; returns data-status. A page
    whose app never started (its packages missing, a script error) fails at once, saying why."""
    while browser.execute_script("return window.gproj === undefined || window.gproj.busy()"):
        if status(browser) == "failed" and \
                browser.execute_script("return window.gproj === undefined"):
            raise AssertionError("the web app did not start: " +
                                 browser.find_element(By.TAG_NAME, "body").text)
        time.sleep(0.05)
    return status(browser)


def open_page(browser, server, query):
    browser.get(server + "/" + query)
    while status(browser) == "idle" and "run=1" in query and \
            browser.execute_script("return !window.gproj || window.gproj.state.runs === 0"):
        time.sleep(0.05)
    return await_idle(browser)


def max_diagonal_gap(mesh):
    """Largest distance between the diagonals of a quad over the mean edge length."""
    v = mesh["vertices"]

    def sub(a, b):
        return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]

    edges = [math.dist(v[f[k]], v[f[(k + 1) % 4]]) for f in mesh["faces"] for k in range(4)]
    mean = sum(edges) / len(edges)
    worst = 0.0
    for a, b, c, d in mesh["faces"]:
        u, w, s = sub(v[c], v[a]), sub(v[d], v[b]), sub(v[b], v[a])
        n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]]
        length = math.sqrt(sum(x * x for x in n))
        worst = max(worst, abs(sum(n[i] * s[i] for i in range(3))) / length / mean)
    return worst


def base_run(browser, server):
    return api(server, "/api/runs/" + browser.execute_script("return window.gproj.state.base"))


def pointer_at(browser, vertex):
    p = browser.execute_script("return window.gproj.vertexOnScreen(arguments[0])", vertex)
    assert p["visible"]
    return int(round(p["x"])), int(round(p["y"]))


def click_button(browser, name):
    browser.find_element(By.XPATH, f"//button[.//div[text()='{name}']]").click()


def test_example_runs_and_the_page_shows_the_run(browser, server):
    assert open_page(browser, server, "?example=noisy_grid_21x21&problem=planarize&run=1") == "converged"
    run = base_run(browser, server)
    assert run["status"] == "converged"
    final = run["report"]["final"]["max_planarity"]
    shown = float(browser.find_element(By.ID, "measure").get_attribute("data-value"))
    assert shown == final
    assert final <= 1e-9
    assert "max_planarity" in browser.find_element(By.ID, "measure").text
    # The mesh shown is the run's result, and it is planar by an independent measure.
    result = run["result"]["output"]
    assert browser.execute_script("return window.gproj.state.result.vertices") == \
        result["vertices"]
    assert max_diagonal_gap(result) < 1e-8
    # The run was shown live: its iterates replaced the view before its end.
    assert browser.execute_script("return window.gproj.state.iterates") >= 1
    # One record per iteration reached the chart (iterations + the start).
    assert browser.execute_script("return window.gproj.state.records.length") == \
        run["report"]["iterations"] + 1
    # Faces are coloured from the run's face_values.
    values = browser.execute_script("return window.gproj.state.faceTable.planarity")
    assert len(values) == 400 and max(values) == pytest.approx(final, rel=1e-6)
    assert browser.execute_script("return window.gproj.state.colourBy") == "planarity"
    assert "planarity / mean edge" in browser.find_element(By.ID, "legend-name").text


def test_a_clicked_vertex_is_fixed_in_the_next_run(browser, server):
    assert open_page(browser, server, "?example=noisy_grid_21x21") == "idle"
    start = browser.execute_script("return window.gproj.state.start.vertices")
    x, y = pointer_at(browser, 220)
    actions = ActionBuilder(browser)
    actions.pointer_action.move_to_location(x, y).click()
    actions.perform()
    assert browser.execute_script("return [...window.gproj.state.fixed]") == [220]
    assert "vertex 220 fixed" in browser.find_element(By.ID, "message").text
    click_button(browser, "Run")
    while status(browser) != "running" and \
            browser.execute_script("return window.gproj.state.runs") == 0:
        time.sleep(0.05)
    assert await_idle(browser) == "converged"
    run = base_run(browser, server)
    out = run["result"]["output"]["vertices"]
    assert out[220] == start[220]  # held bit for bit
    assert max(math.dist(out[v], start[v]) for v in range(len(out))) > 1e-4  # others moved
    assert max_diagonal_gap(run["result"]["output"]) < 1e-8


def test_dragging_a_vertex_re_solves_from_the_result(browser, server):
    assert open_page(browser, server, "?example=noisy_grid_21x21&run=1") == "converged"
    first = base_run(browser, server)
    before = first["result"]["output"]["vertices"]
    x, y = pointer_at(browser, 230)
    actions = ActionBuilder(browser)
    actions.pointer_action.move_to_location(x, y).pointer_down()
    for k in range(1, 9):
        actions.pointer_action.move_to_location(x, y - 5 * k).pause(0.05)
    actions.pointer_action.pointer_up()
    actions.perform()
    assert await_idle(browser) == "converged"
    assert browser.execute_script("return window.gproj.state.resolves") >= 1
    run = base_run(browser, server)
    assert run["id"] != first["id"] and run["status"] == "converged"
    after = run["result"]["output"]["vertices"]
    moved = math.dist(after[230], before[230])
    assert moved > 0.02  # the mean edge is 0.1: the drag moved it by a fifth of an edge or more
    # The dropped vertex stays where it was dropped (it is held), its neighbours followed, and
    # the mesh is planar again to the run's tolerance.
    assert after[230] == browser.execute_script("return window.gproj.state.result.vertices[230]")
    assert math.dist(after[229], before[229]) > 1e-4
    assert max_diagonal_gap(run["result"]["output"]) < 1e-8
    assert 230 in browser.execute_script("return [...window.gproj.state.fixed]")


def generated_grid(rows, columns, seed):
    """A noisy grid on a hyperbolic paraboloid, turned away from the axes: not a shipped mesh."""
    rng = random.Random(seed)
    turn = 0.6
    lines = []
    for i in range(rows):
        for j in range(columns):
            u, w = i / (rows - 1) - 0.5, j / (columns - 1) - 0.5
            x, y = math.cos(turn) * u - math.sin(turn) * w, math.sin(turn) * u + math.cos(turn) * w
            z = 0.8 * u * w + rng.uniform(-0.01, 0.01)
            lines.append(f"v {x + rng.uniform(-0.005, 0.005)} {y} {z}")
    for i in range(rows - 1):
        for j in range(columns - 1):
            a = i * columns + j + 1
            lines.append(f"f {a} {a + 1} {a + columns + 1} {a + columns}")
    return "\n".join(lines) + "\n"


def test_a_mesh_file_opens_and_runs_and_a_bad_one_is_refused(browser, server):
    assert open_page(browser, server, "") == "idle"
    directory = tempfile.mkdtemp()
    path = os.path.join(directory, "saddle_9x7.obj")
    with open(path, "w") as f:
        f.write(generated_grid(9, 7, 3))
    browser.find_element(By.ID, "file").send_keys(path)
    while browser.execute_script("return window.gproj.state.start.vertices.length") != 63:
        time.sleep(0.05)
    assert "saddle_9x7.obj: 63 vertices, 48 faces" in browser.find_element(By.ID, "message").text
    click_button(browser, "Run")
    while browser.execute_script("return window.gproj.state.runs") == 0:
        time.sleep(0.05)
    assert await_idle(browser) == "converged"
    run = base_run(browser, server)
    assert max_diagonal_gap(run["result"]["output"]) < 1e-8
    bad = os.path.join(directory, "bad.obj")
    with open(bad, "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 5\n")
    browser.find_element(By.ID, "file").send_keys(bad)
    while status(browser) != "failed":
        time.sleep(0.05)
    message = browser.find_element(By.ID, "message").text
    assert "bad.obj:4" in message and "vertex 4" in message, message
    assert browser.execute_script("return window.gproj.state.start.vertices.length") == 63


def test_hnet_shows_its_smooth_surface(browser, server):
    assert open_page(browser, server, "?example=enneper_41x41_jitter3&run=1") == "converged"
    surface = browser.execute_script("return window.gproj.state.surface")
    assert surface is not None and len(surface["faces"]) > 1600
    run = base_run(browser, server)
    assert run["status"] == "converged"
    assert len(surface["vertices"]) == len(run["result"]["surface_mesh"]["vertices"])


def test_screenshot_shows_the_coloured_mesh(browser, server):
    from PIL import Image
    browser.get_log("browser")  # the earlier tests' entries (e.g. the refused file's 400)
    assert open_page(browser, server, "?example=noisy_grid_21x21&circular=true&run=1") == "converged"
    # The faces can be coloured by any per-face value of the result: concyclicity here.
    choices = Select(browser.find_element(By.XPATH, "//div[text()='Colour by']/..//select"))
    names = [o.text for o in choices.options]
    assert {"planarity", "concyclicity", "kink_deg", "min_angle_deg"} <= set(names), names
    choices.select_by_visible_text("concyclicity")
    assert browser.execute_script("return window.gproj.state.colourBy") == "concyclicity"
    run = base_run(browser, server)
    assert max(browser.execute_script("return window.gproj.state.faceTable.concyclicity")) == \
        pytest.approx(run["report"]["final"]["max_concyclicity"], rel=1e-6)
    assert "concyclicity / mean edge" in browser.find_element(By.ID, "legend-name").text
    choices.select_by_visible_text("min_angle_deg")
    assert "min angle (degrees)" in browser.find_element(By.ID, "legend-name").text
    choices.select_by_visible_text("concyclicity")
    path = os.path.join(OUT, "web_app_screenshot.png")
    assert browser.save_screenshot(path)
    image = Image.open(path).convert("RGB")
    # The model is drawn where the view is: the centre of the page holds many shades of the
    # faces (lit, coloured), not the background's one.
    w, h = image.size
    centre = image.crop((w // 4, h // 4, w // 2, h // 2))
    assert len(set(centre.getdata())) > 50
    errors = [e for e in browser.get_log("browser") if e["level"] == "SEVERE"]
    assert errors == []


def test_marionette_lifts_the_plan_and_keeps_it(browser, server):
    assert open_page(browser, server, "?example=marionette_plan_21x21&run=1") == "converged"
    run = base_run(browser, server)
    example = api(server, "/api/examples/marionette_plan_21x21")
    plan = example["inputs"]["plan"]["vertices"]
    lifted = browser.execute_script("return window.gproj.state.result.vertices")
    assert lifted == run["result"]["output"]["vertices"]
    # Every vertex moved vertically only: the plan view is kept; the quads are planar.
    assert max(math.hypot(a[0] - b[0], a[1] - b[1]) for a, b in zip(plan, lifted)) < 1e-12
    assert max(abs(p[2]) for p in lifted) > 0.1
    assert max_diagonal_gap(run["result"]["output"]) < 1e-6
    # The guide values the example sent are the heights of row 0.
    row = example["options"]["row"]
    assert lifted[5][2] == pytest.approx(row[5], abs=1e-9)


def test_weingarten_shows_the_surface_and_its_curvature_diagram(browser, server):
    assert open_page(browser, server, "?example=bump_14x14&run=1") in ("converged",
                                                                     "not-converged")
    run = base_run(browser, server)
    assert run["status"] == status(browser)
    # With a fixed relation the tolerance bounds the relation's residual: that is what is shown.
    assert run["report"]["tolerance_measure"] == "max_relation_residual"
    measure = browser.find_element(By.ID, "measure")
    assert "max_relation_residual" in measure.text
    assert float(measure.get_attribute("data-value")) == \
        run["report"]["final"]["max_relation_residual"]
    # The result shown is the optimised surface sampled as the preview was, so before/after
    # compare vertex by vertex; the diagram is shown beside the view.
    shown = browser.execute_script("return window.gproj.state.result")
    preview = api(server, "/api/examples/bump_14x14")["preview"]
    assert shown == run["result"]["surface_mesh"]
    assert len(shown["vertices"]) == len(preview["vertices"])
    assert max(math.dist(a, b) for a, b in zip(shown["vertices"], preview["vertices"])) > 1e-4
    figure = browser.find_element(By.CSS_SELECTOR, "#figure img")
    assert figure.is_displayed()
    assert run["result"]["diagram"].lstrip().startswith("<")
    assert browser.execute_script("return arguments[0].naturalWidth", figure) > 0
    path = os.path.join(OUT, "web_app_weingarten.png")
    assert browser.save_screenshot(path)
    # The before/after toggle shows the input.
    browser.find_element(By.XPATH, "//div[text()='Show the input']").click()
    assert browser.execute_script("return window.gproj.state.showing") == "before"


def test_bad_links_fail_with_a_message(browser, server):
    assert open_page(browser, server, "?example=no_such_mesh") == "failed"
    message = browser.find_element(By.ID, "message").text
    assert "no example no_such_mesh" in message and "noisy_grid_21x21" in message
    assert open_page(browser, server, "?example=noisy_grid_21x21&tolerence=1e-9") == "failed"
    assert "tolerence: planarize has no such option" in browser.find_element(By.ID, "message").text
    assert open_page(browser, server, "?example=noisy_grid_21x21&problem=weingarten&run=1") == \
        "failed"
    assert "weingarten takes a B-spline surface" in browser.find_element(By.ID, "message").text


def test_with_a_token_the_page_sends_it_with_every_request(browser):
    process = subprocess.Popen([BINARY, "serve", "--port", "0", "--token", "web-app-token"],
                               stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    try:
        match = re.search(r"listening on http://127\.0\.0\.1:(\d+)/", process.stdout.readline())
        assert match
        url = f"http://127.0.0.1:{match.group(1)}"
        # Without it the page loads but the service refuses it everything.
        assert open_page(browser, url, "?example=noisy_grid_21x21") == "failed"
        assert "needs its token" in browser.find_element(By.ID, "message").text
        assert open_page(browser, url, "?token=web-app-token&example=noisy_grid_21x21&run=1") \
            == "converged"
        assert browser.execute_script("return window.gproj.state.records.length") > 2
    finally:
        process.terminate()
        assert process.wait() == 0


def test_anet_on_the_hnet_example_makes_the_stars_planar(browser, server):
    import numpy
    assert open_page(browser, server,
                     "?example=enneper_41x41_jitter3&problem=anet&run=1") == "converged"
    run = base_run(browser, server)
    assert run["problem"] == "anet"
    assert browser.execute_script("return window.gproj.state.colourBy") == "star_planarity"
    final = run["report"]["final"]["max_star_planarity"]
    assert final <= run["report"]["tolerance"]
    # Independently: every inner vertex of valence 4 and its four neighbours lie in a plane (the
    # smallest singular value of the five centred points, over the mean edge).
    mesh = run["result"]["output"]
    v = numpy.array(mesh["vertices"])
    neighbours = {}
    for face in mesh["faces"]:
        for k, a in enumerate(face):
            neighbours.setdefault(a, set()).update({face[k - 1], face[(k + 1) % len(face)]})
    edges = [numpy.linalg.norm(v[f[k]] - v[f[k - 1]]) for f in mesh["faces"] for k in range(4)]
    worst, stars = 0.0, 0
    valence = {a: sum(a in f for f in mesh["faces"]) for a in neighbours}
    for a, ring in neighbours.items():
        if len(ring) != 4 or valence[a] != 4:
            continue
        points = v[[a, *ring]]
        worst = max(worst, numpy.linalg.svd(points - points.mean(axis=0))[1][2])
        stars += 1
    assert stars > 1000
    assert worst / numpy.mean(edges) < 1e-5


def test_dropping_the_shipped_grid_and_running_it(browser, server):
    """What a new user does first: drop the noisy grid on the page and press Run."""
    assert open_page(browser, server, "?example=revolution_13x17") == "idle"
    source = os.path.join(os.path.dirname(__file__), "..", "..", "examples", "data",
                          "noisy_grid_21x21.obj")
    with open(source) as f:
        text = f.read()
    browser.execute_script("""
        const transfer = new DataTransfer();
        transfer.items.add(new File([arguments[0]], 'noisy_grid_21x21.obj', {type: 'text/plain'}));
        window.dispatchEvent(new DragEvent('drop', {dataTransfer: transfer, bubbles: true,
                                                    cancelable: true}));""", text)
    while browser.execute_script("return window.gproj.state.start.vertices.length") != 441:
        time.sleep(0.05)
    assert await_idle(browser) == "idle"
    assert "noisy_grid_21x21.obj: 441 vertices, 400 faces" in \
        browser.find_element(By.ID, "message").text
    click_button(browser, "Run")
    while browser.execute_script("return window.gproj.state.runs") == 0:
        time.sleep(0.05)
    assert await_idle(browser) == "converged"
    run = base_run(browser, server)
    assert run["problem"] == "planarize"
    assert max_diagonal_gap(run["result"]["output"]) < 1e-8
    # The example's options (circular) were left with it: the file ran with the defaults.
    assert run["report"]["options"]["circular"] is False
    # The dropped file's vertices went in, in the file's order (the mean edge is 0.1).
    example = api(server, "/api/examples/noisy_grid_21x21")["inputs"]["mesh"]
    assert max(math.dist(a, b) for a, b in zip(run["result"]["output"]["vertices"],
                                               example["vertices"])) < 0.1
