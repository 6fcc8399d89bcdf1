/*
 * indi_client.cpp - the INDI client of the rig (indi.h): libindi's
 * INDI::BaseClient, whose own thread reads the server and calls us back.
 * Each callback copies what we need (state, numbers, switches, the last
 * BLOB) into a table under one mutex and wakes the waiters, so the C side
 * reads consistent copies and never touches libindi's objects while its
 * thread rewrites them.  A lost server (indiserver killed) ends the
 * client: the next rig_indi_server() makes a fresh one.
 */
#include <libindi/baseclient.h>
#include <libindi/basedevice.h>

#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <string>
#include <vector>

extern "C" {
#include "rig/indi.h"
}

namespace {

struct Prop {
	bool defined = false;
	int state = RIG_INDI_IDLE;
	unsigned long gen = 0;
	std::map<std::string, double> num, min, max;
	std::map<std::string, int> sw;
	std::vector<unsigned char> blob;
	unsigned long blob_gen = 0;
};

struct Mirror {
	std::mutex mu;
	std::condition_variable cv;
	std::map<std::string, Prop> props;	/* "device\nproperty" */
	std::map<std::string, std::string> msg;	/* last message per device */
	unsigned long gen = 1;
	bool alive = false;
};

std::string key(const char *dev, const char *prop)
{
	return std::string(dev) + "\n" + prop;
}

int state_of(IPState s)
{
	switch (s) {
	case IPS_OK: return RIG_INDI_OK;
	case IPS_BUSY: return RIG_INDI_BUSY;
	case IPS_ALERT: return RIG_INDI_ALERT;
	default: return RIG_INDI_IDLE;
	}
}

class Client : public INDI::BaseClient {
public:
	explicit Client(Mirror *m) : m_(m) {}

	void newProperty(INDI::Property p) override { copy(p); }
	void updateProperty(INDI::Property p) override { copy(p); }
	void removeProperty(INDI::Property p) override
	{
		std::lock_guard<std::mutex> g(m_->mu);
		Prop &q = m_->props[key(p.getDeviceName(), p.getName())];

		q.defined = false;
		q.gen = ++m_->gen;
		m_->cv.notify_all();
	}
	void removeDevice(INDI::BaseDevice d) override
	{
		std::lock_guard<std::mutex> g(m_->mu);
		std::string pre = std::string(d.getDeviceName()) + "\n";

		for (auto &kv : m_->props)
			if (kv.first.compare(0, pre.size(), pre) == 0)
				kv.second.defined = false;
		++m_->gen;
		m_->cv.notify_all();
	}
	void newMessage(INDI::BaseDevice d, int id) override
	{
		std::string text = d.messageQueue(id);
		std::lock_guard<std::mutex> g(m_->mu);

		m_->msg[d.getDeviceName()] = text;
	}
	void serverConnected() override
	{
		std::lock_guard<std::mutex> g(m_->mu);

		m_->alive = true;
		++m_->gen;
		m_->cv.notify_all();
	}
	void serverDisconnected(int) override
	{
		std::lock_guard<std::mutex> g(m_->mu);

		m_->alive = false;
		for (auto &kv : m_->props)
			kv.second.defined = false;
		++m_->gen;
		m_->cv.notify_all();
	}

private:
	void copy(INDI::Property p)
	{
		std::lock_guard<std::mutex> g(m_->mu);
		Prop &q = m_->props[key(p.getDeviceName(), p.getName())];

		q.defined = true;
		q.state = state_of(p.getState());
		q.gen = ++m_->gen;
		if (p.getType() == INDI_NUMBER) {
			for (auto &e : *p.getNumber()) {
				q.num[e.getName()] = e.getValue();
				q.min[e.getName()] = e.getMin();
				q.max[e.getName()] = e.getMax();
			}
		} else if (p.getType() == INDI_SWITCH) {
			for (auto &e : *p.getSwitch())
				q.sw[e.getName()] = e.getState() == ISS_ON;
		} else if (p.getType() == INDI_BLOB) {
			/* The first element with data: CCD1's one image. */
			for (auto &e : *p.getBLOB()) {
				const unsigned char *b = static_cast<
					const unsigned char *>(e.getBlob());

				if (!b || e.getBlobLen() <= 0)
					continue;
				q.blob.assign(b, b + e.getBlobLen());
				q.blob_gen = q.gen;
				break;
			}
		}
		m_->cv.notify_all();
	}

	Mirror *m_;
};

} /* namespace */

struct rig_indi {
	std::string host;
	int port;
	Mirror m;
	Client *cl = nullptr;
	std::chrono::steady_clock::time_point since;	/* connected at */
	std::vector<std::string> blob_devs;
	/* Our messages, one per (device, property, size), reused: libindi
	 * 1.9.9 never frees a property made by count (LeakSanitizer). */
	std::map<std::string, INDI::PropertyNumber> out_num;
	std::map<std::string, INDI::PropertySwitch> out_sw;
};

extern "C" {

struct rig_indi *rig_indi_new(const char *host, int port)
{
	rig_indi *c = new (std::nothrow) rig_indi;

	if (!c)
		return nullptr;
	c->host = host;
	c->port = port;
	return c;
}

static void drop_client(struct rig_indi *c)
{
	if (!c->cl)
		return;
	c->cl->disconnectServer();
	delete c->cl;
	c->cl = nullptr;
	std::lock_guard<std::mutex> g(c->m.mu);
	c->m.alive = false;
	for (auto &kv : c->m.props)
		kv.second.defined = false;
	++c->m.gen;
}

void rig_indi_free(struct rig_indi *c)
{
	if (!c)
		return;
	drop_client(c);
	delete c;
}

int rig_indi_alive(struct rig_indi *c)
{
	std::lock_guard<std::mutex> g(c->m.mu);

	return c->cl && c->m.alive;
}

int rig_indi_server(struct rig_indi *c, double timeout_s)
{
	if (rig_indi_alive(c))
		return RIG_OK;
	drop_client(c);
	c->cl = new (std::nothrow) Client(&c->m);
	if (!c->cl)
		return RIG_ENOMEM;
	c->cl->setServer(c->host.c_str(), (unsigned)c->port);
	c->cl->setConnectionTimeout((uint32_t)timeout_s,
		(uint32_t)((timeout_s - (uint32_t)timeout_s) * 1e6));
	if (!c->cl->connectServer()) {
		drop_client(c);
		return RIG_EDISCONNECT;
	}
	{
		std::lock_guard<std::mutex> g(c->m.mu);
		c->m.alive = true;	/* serverConnected may come later */
	}
	c->since = std::chrono::steady_clock::now();
	for (auto &d : c->blob_devs)
		c->cl->setBLOBMode(B_ALSO, d.c_str(), nullptr);
	return RIG_OK;
}

void rig_indi_drop(struct rig_indi *c)
{
	drop_client(c);
}

double rig_indi_age(struct rig_indi *c)
{
	if (!rig_indi_alive(c))
		return 0;
	return std::chrono::duration<double>(
		std::chrono::steady_clock::now() - c->since).count();
}

void rig_indi_want_blobs(struct rig_indi *c, const char *dev)
{
	bool known = false;

	for (auto &d : c->blob_devs)
		known = known || d == dev;
	if (!known)
		c->blob_devs.push_back(dev);
	if (c->cl && rig_indi_alive(c))
		c->cl->setBLOBMode(B_ALSO, dev, nullptr);
}

/* The property under the lock; nullptr when not defined. */
static const Prop *find(struct rig_indi *c, const char *dev, const char *prop)
{
	auto it = c->m.props.find(key(dev, prop));

	return it == c->m.props.end() || !it->second.defined ? nullptr
							      : &it->second;
}

static void fill(const Prop *q, struct rig_indi_prop *p)
{
	if (!p)
		return;
	p->defined = q != nullptr;
	p->state = q ? q->state : RIG_INDI_IDLE;
	p->gen = q ? q->gen : 0;
}

/* Our copy of a property for a read (the lock held): its state into p,
 * RIG_EDISCONNECT without a live server, RIG_ESTATE when not defined. */
static int lookup(struct rig_indi *c, const char *dev, const char *prop,
		  struct rig_indi_prop *p, const Prop **q)
{
	*q = find(c, dev, prop);
	fill(*q, p);
	if (!c->cl || !c->m.alive)
		return RIG_EDISCONNECT;
	return *q ? RIG_OK : RIG_ESTATE;
}

/* The property defined with these elements, per our copy. */
static int check_elems(struct rig_indi *c, const char *dev, const char *prop,
		       int type, int n, const char *const *elems)
{
	std::lock_guard<std::mutex> g(c->m.mu);
	const Prop *q = find(c, dev, prop);

	if (!c->cl || !c->m.alive)
		return RIG_EDISCONNECT;
	if (!q)
		return RIG_ESTATE;
	for (int i = 0; i < n; i++)
		if (type == INDI_NUMBER ? !q->num.count(elems[i])
					: !q->sw.count(elems[i]))
			return RIG_EINVAL;
	return RIG_OK;
}

int rig_indi_prop(struct rig_indi *c, const char *dev, const char *prop,
		  struct rig_indi_prop *p)
{
	std::lock_guard<std::mutex> g(c->m.mu);

	fill(find(c, dev, prop), p);
	return c->cl && c->m.alive ? RIG_OK : RIG_EDISCONNECT;
}

int rig_indi_number(struct rig_indi *c, const char *dev, const char *prop,
		    const char *elem, double *v, double *min, double *max,
		    struct rig_indi_prop *p)
{
	std::lock_guard<std::mutex> g(c->m.mu);
	const Prop *q;
	int rc = lookup(c, dev, prop, p, &q);

	if (rc != RIG_OK)
		return rc;
	auto it = q->num.find(elem);
	if (it == q->num.end())
		return RIG_EINVAL;
	if (v)
		*v = it->second;
	if (min)
		*min = q->min.at(elem);
	if (max)
		*max = q->max.at(elem);
	return RIG_OK;
}

int rig_indi_switch(struct rig_indi *c, const char *dev, const char *prop,
		    const char *elem, int *on, struct rig_indi_prop *p)
{
	std::lock_guard<std::mutex> g(c->m.mu);
	const Prop *q;
	int rc = lookup(c, dev, prop, p, &q);

	if (rc != RIG_OK)
		return rc;
	auto it = q->sw.find(elem);
	if (it == q->sw.end())
		return RIG_EINVAL;
	*on = it->second;
	return RIG_OK;
}

int rig_indi_blob(struct rig_indi *c, const char *dev, const char *prop,
		  unsigned long after_gen, unsigned char **data, size_t *len,
		  unsigned long *gen)
{
	std::lock_guard<std::mutex> g(c->m.mu);
	auto it = c->m.props.find(key(dev, prop));

	if (gen)
		*gen = it == c->m.props.end() ? 0 : it->second.blob_gen;
	if (it == c->m.props.end() || it->second.blob_gen <= after_gen ||
	    it->second.blob.empty())
		return RIG_EAGAIN;
	*len = it->second.blob.size();
	*data = static_cast<unsigned char *>(std::malloc(*len));
	if (!*data)
		return RIG_ENOMEM;
	std::memcpy(*data, it->second.blob.data(), *len);
	return RIG_OK;
}

/* The message is built from a property of our own, never from the
 * client's copy: its reader thread rewrites that copy (an exposure's
 * countdown to 0) between our setting a value and the send. */
int rig_indi_send_numbers(struct rig_indi *c, const char *dev,
			  const char *prop, int n, const char *const *elems,
			  const double *values)
{
	int rc = check_elems(c, dev, prop, INDI_NUMBER, n, elems);

	if (rc != RIG_OK)
		return rc;
	std::string k = key(dev, prop) + "\n" + std::to_string(n);
	auto it = c->out_num.find(k);
	if (it == c->out_num.end())
		it = c->out_num.emplace(k, INDI::PropertyNumber((size_t)n))
			.first;
	INDI::PropertyNumber &v = it->second;
	v.setDeviceName(dev);
	v.setName(prop);
	for (int i = 0; i < n; i++) {
		v[i].setName(elems[i]);
		v[i].setValue(values[i]);
	}
	c->cl->sendNewNumber(v);
	return RIG_OK;
}

/* One element on: for a one-of-many switch the driver turns the others
 * off (IUUpdateSwitch), as indi_setprop's one-element messages rely on. */
int rig_indi_send_switch(struct rig_indi *c, const char *dev,
			 const char *prop, const char *elem)
{
	int rc = check_elems(c, dev, prop, INDI_SWITCH, 1, &elem);

	if (rc != RIG_OK)
		return rc;
	std::string k = key(dev, prop);
	auto it = c->out_sw.find(k);
	if (it == c->out_sw.end())
		it = c->out_sw.emplace(k, INDI::PropertySwitch((size_t)1))
			.first;
	INDI::PropertySwitch &v = it->second;
	v.setDeviceName(dev);
	v.setName(prop);
	v[0].setName(elem);
	v[0].setState(ISS_ON);
	c->cl->sendNewSwitch(v);
	return RIG_OK;
}

void rig_indi_message(struct rig_indi *c, const char *dev, char *buf,
		      size_t size)
{
	std::lock_guard<std::mutex> g(c->m.mu);
	auto it = c->m.msg.find(dev);
	std::string t = it == c->m.msg.end() ? std::string() : it->second;

	/* One line: the driver's own words, newlines folded. */
	for (auto &ch : t)
		if (ch == '\n' || ch == '\r')
			ch = ' ';
	std::snprintf(buf, size, "%s", t.c_str());
}

unsigned long rig_indi_gen(struct rig_indi *c)
{
	std::lock_guard<std::mutex> g(c->m.mu);

	return c->m.gen;
}

int rig_indi_wait(struct rig_indi *c, unsigned long *gen, double timeout_s)
{
	std::unique_lock<std::mutex> g(c->m.mu);
	auto until = std::chrono::steady_clock::now() +
		std::chrono::microseconds((long long)(timeout_s * 1e6));

	while (c->m.gen <= *gen && c->m.alive &&
	       std::chrono::steady_clock::now() < until)
		c->m.cv.wait_until(g, until);
	if (c->m.gen > *gen) {
		*gen = c->m.gen;
		return RIG_OK;
	}
	return c->m.alive ? RIG_ETIMEOUT : RIG_EDISCONNECT;
}

} /* extern "C" */
