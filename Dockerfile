# The aiobt image: every service of docker-compose.yml runs it (`aiobt <service> ...`).
# No credentials are baked in: they come from the environment at run time.
FROM python:3.11-slim

ENV PYTHONUNBUFFERED=1 PIP_NO_CACHE_DIR=1 PIP_DISABLE_PIP_VERSION_CHECK=1
RUN apt-get update \
    && apt-get install -y --no-install-recommends build-essential \
    && rm -rf /var/lib/apt/lists/*

WORKDIR /app
COPY pyproject.toml README.md ./
COPY src ./src
COPY services ./services
COPY trees ./trees
# editable: src/aiobt/trees links to /app/trees (Nav2's trees, shipped as aiobt.trees)
RUN pip install -e . && useradd --create-home --uid 1000 aiobt
USER aiobt

ENTRYPOINT ["aiobt"]
CMD ["--help"]
